// A program started by a test as a separate process (posix_spawn) in a
// process group of its own, with its output sent to a log file; destroyed
// while it runs, its group is killed, the program and whatever it started.
#pragma once

#include <sys/types.h>

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace lineloc::test {

class ChildProcess {
 public:
  // Starts `program` with `args` in the test's environment plus
  // `environment` ("NAME=value", taking precedence); stdout and stderr go to
  // `log_path`.
  ChildProcess(const std::string& program, const std::vector<std::string>& args,
               const std::string& log_path, const std::vector<std::string>& environment = {});
  ~ChildProcess();
  ChildProcess(const ChildProcess&) = delete;
  ChildProcess& operator=(const ChildProcess&) = delete;

  // Waits for the exit; returns the exit code, or nullopt on timeout. A
  // process ended by a signal returns 128 + the signal number.
  std::optional<int> wait(int timeout_ms);
  void signal(int signal_number);
  bool running();
  // The most memory the running process has held resident so far (VmHWM, KiB).
  int64_t peakResidentKiB() const;

 private:
  pid_t pid_ = -1;
  std::optional<int> exit_code_;
};

}  // namespace lineloc::test
