// A real gpsd fed an NMEA log by gpsfake (gpsd's own test tool), on a free
// port of loopback, for tests of the robot's GNSS input; stopped on
// destruction.
#pragma once

#include <memory>
#include <string>

#include "tests/support/child_process.h"

namespace lineloc::test {

class FakeGpsd {
 public:
  // Starts gpsfake on `nmea_log`, one sentence every `cycle_s` seconds, over
  // and over; gpsd waits for its first client before the log starts. gpsfake
  // logs to `log_path` each time it starts the log again. Throws
  // std::runtime_error when gpsd does not listen within 30 s.
  FakeGpsd(const std::string& nmea_log, double cycle_s, const std::string& log_path);

  const std::string& port() const { return port_; }

 private:
  std::string port_;
  std::unique_ptr<ChildProcess> process_;
};

}  // namespace lineloc::test
