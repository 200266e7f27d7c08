// Reads text lines (NMEA sentences, IMU CSV rows) from a sensor's stream: a
// serial device such as /dev/ttyUSB0, set to raw mode, 8 data bits, no
// parity, one stop bit and the given baud rate (termios(3)); a FIFO, held
// open for writing too so that the program feeding it may stop and start
// again without ending the stream; or a file, which ends at its end. Lines
// end at '\n'; a trailing '\r' is removed; a line longer than
// kMaxSensorLineLength is garbage (wrong baud rate, binary protocol) and is
// dropped and counted.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace lineloc {

inline constexpr size_t kMaxSensorLineLength = 256;

class SensorLineReader {
 public:
  // Throws std::invalid_argument for a baud rate termios does not have, and
  // std::runtime_error naming the device when it cannot be opened or configured.
  SensorLineReader(const std::string& device, int baud_rate);
  ~SensorLineReader();
  SensorLineReader(const SensorLineReader&) = delete;
  SensorLineReader& operator=(const SensorLineReader&) = delete;

  // The complete lines received within `timeout_ms` (returns as soon as at
  // least one line is complete, or at the end of a file). Throws
  // std::runtime_error on a read error.
  std::vector<std::string> readLines(int timeout_ms);

  // True once a file (or a serial device that hung up) has no more to read.
  bool ended() const { return ended_; }
  int64_t overlongLines() const { return overlong_lines_; }

 private:
  void appendBytes(const char* data, size_t size, std::vector<std::string>& lines);

  std::string device_;
  int fd_ = -1;
  std::string partial_;
  bool discarding_ = false;
  bool ended_ = false;
  int64_t overlong_lines_ = 0;
};

}  // namespace lineloc
