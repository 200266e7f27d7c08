// Reads text lines (NMEA sentences) from a serial device such as /dev/ttyUSB0:
// raw mode, 8 data bits, no parity, one stop bit, the given baud rate
// (termios(3)). Lines end at '\n'; a trailing '\r' is removed; a line longer
// than kMaxSerialLineLength is garbage (wrong baud rate, binary protocol) and
// is dropped and counted.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace lineloc {

inline constexpr size_t kMaxSerialLineLength = 256;

class SerialLineReader {
 public:
  // Throws std::invalid_argument for a baud rate termios does not have, and
  // std::runtime_error naming the device when it cannot be opened or configured.
  SerialLineReader(const std::string& device, int baud_rate);
  ~SerialLineReader();
  SerialLineReader(const SerialLineReader&) = delete;
  SerialLineReader& operator=(const SerialLineReader&) = delete;

  // The complete lines received within `timeout_ms` (returns as soon as at
  // least one line is complete). Throws std::runtime_error on a read error.
  std::vector<std::string> readLines(int timeout_ms);

  int64_t overlongLines() const { return overlong_lines_; }

 private:
  void appendBytes(const char* data, size_t size, std::vector<std::string>& lines);

  std::string device_;
  int fd_ = -1;
  std::string partial_;
  bool discarding_ = false;
  int64_t overlong_lines_ = 0;
};

}  // namespace lineloc
