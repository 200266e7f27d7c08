#include "tests/support/fake_gpsd.h"

#include <arpa/inet.h>
#include <fmt/format.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <chrono>
#include <stdexcept>
#include <thread>

namespace lineloc::test {
namespace {

// A TCP port of loopback that nothing listens on now.
int freePort() {
  const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  socklen_t length = sizeof(address);
  if (fd < 0 || ::bind(fd, reinterpret_cast<sockaddr*>(&address), sizeof(address)) != 0 ||
      ::getsockname(fd, reinterpret_cast<sockaddr*>(&address), &length) != 0) {
    throw std::runtime_error("no free port on loopback");
  }
  ::close(fd);
  return ntohs(address.sin_port);
}

bool listening(int port) {
  const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  address.sin_port = htons(static_cast<uint16_t>(port));
  const bool connected = ::connect(fd, reinterpret_cast<sockaddr*>(&address), sizeof(address)) == 0;
  ::close(fd);
  return connected;
}

}  // namespace

FakeGpsd::FakeGpsd(const std::string& nmea_log, double cycle_s, const std::string& log_path) {
  const int port = freePort();
  port_ = std::to_string(port);
  process_ = std::make_unique<ChildProcess>(
      "/usr/bin/gpsfake",
      std::vector<std::string>{"-v", "-P", port_, "-c", fmt::format("{}", cycle_s), nmea_log},
      log_path);
  for (int attempt = 0; attempt < 600; ++attempt) {
    if (listening(port)) {
      return;
    }
    if (!process_->running()) {
      break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  throw std::runtime_error(
      fmt::format("gpsfake's gpsd is not listening on port {} (log: {})", port_, log_path));
}

}  // namespace lineloc::test
