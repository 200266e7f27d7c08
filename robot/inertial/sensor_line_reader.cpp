#include "robot/inertial/sensor_line_reader.h"

#include <fcntl.h>
#include <fmt/format.h>
#include <poll.h>
#include <sys/stat.h>
#include <termios.h>
#include <unistd.h>

#include <array>
#include <cerrno>
#include <cstring>
#include <stdexcept>
#include <utility>

namespace lineloc {
namespace {

constexpr std::pair<int, speed_t> kBaudRates[] = {
    {2400, B2400},   {4800, B4800},     {9600, B9600},     {19200, B19200},   {38400, B38400},
    {57600, B57600}, {115200, B115200}, {230400, B230400}, {460800, B460800}, {921600, B921600}};
constexpr size_t kReadChunk = 512;

speed_t speedFor(int baud_rate) {
  for (const auto& [rate, speed] : kBaudRates) {
    if (rate == baud_rate) {
      return speed;
    }
  }
  throw std::invalid_argument(fmt::format("unsupported serial baud rate {}", baud_rate));
}

}  // namespace

SensorLineReader::SensorLineReader(const std::string& device, int baud_rate) : device_(device) {
  const speed_t speed = speedFor(baud_rate);
  struct stat status {};
  const bool fifo = ::stat(device.c_str(), &status) == 0 && S_ISFIFO(status.st_mode);
  fd_ = ::open(device.c_str(), (fifo ? O_RDWR : O_RDONLY) | O_NOCTTY | O_NONBLOCK | O_CLOEXEC);
  if (fd_ < 0) {
    throw std::runtime_error(
        fmt::format("cannot open sensor stream '{}': {}", device, std::strerror(errno)));
  }
  if (!::isatty(fd_)) {
    return;  // a FIFO or a file: no line settings
  }
  termios options{};
  if (::tcgetattr(fd_, &options) != 0) {
    const std::string why = std::strerror(errno);
    ::close(fd_);
    throw std::runtime_error(fmt::format("cannot read the settings of '{}': {}", device, why));
  }
  ::cfmakeraw(&options);
  options.c_cflag |= CLOCAL | CREAD;
  options.c_cflag &= ~(CSTOPB | PARENB);
  ::cfsetispeed(&options, speed);
  ::cfsetospeed(&options, speed);
  if (::tcsetattr(fd_, TCSANOW, &options) != 0) {
    const std::string why = std::strerror(errno);
    ::close(fd_);
    throw std::runtime_error(fmt::format("cannot configure serial device '{}': {}", device, why));
  }
}

SensorLineReader::~SensorLineReader() {
  if (fd_ >= 0) {
    ::close(fd_);
  }
}

std::vector<std::string> SensorLineReader::readLines(int timeout_ms) {
  std::vector<std::string> lines;
  pollfd request{fd_, POLLIN, 0};
  while (lines.empty() && !ended_) {
    const int ready = ::poll(&request, 1, timeout_ms);
    if (ready < 0 && errno == EINTR) {
      continue;
    }
    if (ready < 0) {
      throw std::runtime_error(
          fmt::format("poll on sensor stream '{}': {}", device_, std::strerror(errno)));
    }
    if (ready == 0) {
      break;
    }
    std::array<char, kReadChunk> buffer{};
    const ssize_t count = ::read(fd_, buffer.data(), buffer.size());
    if (count < 0 && (errno == EAGAIN || errno == EINTR)) {
      continue;
    }
    if (count < 0) {
      throw std::runtime_error(
          fmt::format("read from sensor stream '{}': {}", device_, std::strerror(errno)));
    }
    if (count == 0) {
      ended_ = true;
      break;
    }
    appendBytes(buffer.data(), static_cast<size_t>(count), lines);
  }
  return lines;
}

void SensorLineReader::appendBytes(const char* data, size_t size, std::vector<std::string>& lines) {
  for (size_t i = 0; i < size; ++i) {
    const char c = data[i];
    if (c == '\n') {
      if (!discarding_) {
        if (!partial_.empty() && partial_.back() == '\r') {
          partial_.pop_back();
        }
        lines.push_back(std::move(partial_));
      }
      partial_.clear();
      discarding_ = false;
    } else if (!discarding_) {
      partial_.push_back(c);
      if (partial_.size() > kMaxSensorLineLength) {
        ++overlong_lines_;
        discarding_ = true;
        partial_.clear();
      }
    }
  }
}

}  // namespace lineloc
