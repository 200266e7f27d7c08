// The tests' network with jitter (tests/support/network_jitter): a burst of
// datagrams sent back to back through it all arrive, intact, out of order;
// sent without it, loopback keeps their order.
#include <arpa/inet.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <vector>

#include "tests/support/child_process.h"
#include "tests/support/test_dds.h"

namespace lineloc {
namespace {

constexpr int kDatagrams = 200;

class Receiver {
 public:
  Receiver() : socket_(socket(AF_INET, SOCK_DGRAM, 0)) {
    sockaddr_in address{};
    address.sin_family = AF_INET;
    address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    EXPECT_EQ(bind(socket_, reinterpret_cast<sockaddr*>(&address), sizeof(address)), 0);
    socklen_t length = sizeof(address);
    getsockname(socket_, reinterpret_cast<sockaddr*>(&address), &length);
    port_ = ntohs(address.sin_port);
    const timeval timeout{5, 0};
    setsockopt(socket_, SOL_SOCKET, SO_RCVTIMEO, &timeout, sizeof(timeout));
    const int buffer_bytes = 1 << 20;
    setsockopt(socket_, SOL_SOCKET, SO_RCVBUF, &buffer_bytes, sizeof(buffer_bytes));
  }
  ~Receiver() { close(socket_); }

  int port() const { return port_; }

  // The numbers of the datagrams received, in order of arrival, until
  // `count` have come or none came for 5 s.
  std::vector<uint32_t> receive(int count) const {
    std::vector<uint32_t> numbers;
    uint32_t number = 0;
    while (static_cast<int>(numbers.size()) < count &&
           recv(socket_, &number, sizeof(number), 0) == sizeof(number)) {
      numbers.push_back(number);
    }
    return numbers;
  }

 private:
  int socket_;
  int port_ = 0;
};

std::vector<uint32_t> sendBurst(const std::vector<std::string>& environment) {
  const Receiver receiver;
  const std::string log =
      (std::filesystem::temp_directory_path() / ("udp_burst_" + std::to_string(getpid()) + ".log"))
          .string();
  test::ChildProcess burst(UDP_BURST, {std::to_string(receiver.port()), std::to_string(kDatagrams)},
                           log, environment);
  EXPECT_EQ(burst.wait(10'000), 0);
  std::filesystem::remove(log);
  return receiver.receive(kDatagrams);
}

TEST(NetworkJitter, DatagramsAllArriveOutOfOrder) {
  std::vector<uint32_t> numbers = sendBurst(test::networkJitterEnvironment(50));
  ASSERT_EQ(numbers.size(), static_cast<size_t>(kDatagrams));
  EXPECT_FALSE(std::is_sorted(numbers.begin(), numbers.end()));
  std::sort(numbers.begin(), numbers.end());
  for (uint32_t i = 0; i < kDatagrams; ++i) {
    EXPECT_EQ(numbers[i], i);
  }
}

TEST(NetworkJitter, WithoutItLoopbackKeepsTheOrder) {
  const std::vector<uint32_t> numbers = sendBurst({});
  ASSERT_EQ(numbers.size(), static_cast<size_t>(kDatagrams));
  EXPECT_TRUE(std::is_sorted(numbers.begin(), numbers.end()));
}

}  // namespace
}  // namespace lineloc
