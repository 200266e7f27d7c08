// Sends datagrams numbered 0 .. N-1 (a 4-byte count each), back to back, to
// 127.0.0.1:PORT with sendmsg: the network_jitter library's test traffic.
// Usage: udp_burst PORT N
#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: udp_burst PORT N\n");
    return 2;
  }
  const int port = std::atoi(argv[1]);
  const int count = std::atoi(argv[2]);
  const int socket_fd = socket(AF_INET, SOCK_DGRAM, 0);
  sockaddr_in destination{};
  destination.sin_family = AF_INET;
  destination.sin_port = htons(static_cast<uint16_t>(port));
  destination.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  for (uint32_t i = 0; i < static_cast<uint32_t>(count); ++i) {
    iovec payload{&i, sizeof(i)};
    msghdr message{};
    message.msg_name = &destination;
    message.msg_namelen = sizeof(destination);
    message.msg_iov = &payload;
    message.msg_iovlen = 1;
    if (sendmsg(socket_fd, &message, 0) != static_cast<ssize_t>(sizeof(i))) {
      std::perror("sendmsg");
      return 1;
    }
  }
  close(socket_fd);
  return 0;
}
