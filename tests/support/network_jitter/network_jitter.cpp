// A network with jitter for a test's processes, loaded with LD_PRELOAD: each
// UDP datagram the process sends (sendmsg, which Cyclone DDS sends all its
// packets with) leaves after a delay drawn uniformly from
// [0, LINELOC_TEST_SEND_JITTER_MS] milliseconds, so that datagrams arrive
// late and out of order, as through netem's "delay 0ms Jms" (which needs
// privileges a test does not have). Other sockets, and datagrams with
// ancillary data, are sent at once.
//
// A delayed datagram is copied, with its destination and a duplicate of its
// socket (so that a socket closed meanwhile cannot be confused with a new
// one of the same number), and sent by a thread of this library at its time.
// Its sender is told it was sent in full. A process that exits sends what
// it has in flight first; one killed loses it.
#include <dlfcn.h>
#include <sys/socket.h>
#include <unistd.h>

#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <mutex>
#include <queue>
#include <random>
#include <thread>
#include <vector>

namespace {

using SendMsg = ssize_t (*)(int, const msghdr*, int);
using Clock = std::chrono::steady_clock;

SendMsg realSendMsg() {
  static const auto real = reinterpret_cast<SendMsg>(dlsym(RTLD_NEXT, "sendmsg"));
  return real;
}

struct Datagram {
  Clock::time_point due;
  int socket = -1;
  int flags = 0;
  sockaddr_storage destination{};
  socklen_t destination_length = 0;
  std::vector<char> payload;

  bool operator>(const Datagram& other) const { return due > other.due; }
};

class DelayLine {
 public:
  explicit DelayLine(double jitter_ms)
      : jitter_(0.0, jitter_ms * 1e-3), random_(std::random_device{}()) {
    std::thread([this] { run(); }).detach();
  }

  void push(Datagram datagram) {
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      datagram.due = Clock::now() + std::chrono::duration_cast<Clock::duration>(
                                        std::chrono::duration<double>(jitter_(random_)));
      waiting_.push(std::move(datagram));
    }
    wake_.notify_all();
  }

  // Blocks until every datagram pushed has been sent.
  void drain() {
    std::unique_lock<std::mutex> lock(mutex_);
    wake_.wait(lock, [this] { return waiting_.empty() && !sending_; });
  }

 private:
  void run() {
    std::unique_lock<std::mutex> lock(mutex_);
    for (;;) {
      if (waiting_.empty()) {
        wake_.wait(lock);
        continue;
      }
      // A copy: wait_until reads its deadline after a push may have moved the heap.
      const Clock::time_point due = waiting_.top().due;
      if (wake_.wait_until(lock, due) == std::cv_status::no_timeout &&
          Clock::now() < waiting_.top().due) {
        continue;
      }
      Datagram datagram = waiting_.top();
      waiting_.pop();
      sending_ = true;
      lock.unlock();
      send(datagram);
      lock.lock();
      sending_ = false;
      wake_.notify_all();
    }
  }

  static void send(Datagram& datagram) {
    iovec payload{datagram.payload.data(), datagram.payload.size()};
    msghdr message{};
    message.msg_name = &datagram.destination;
    message.msg_namelen = datagram.destination_length;
    message.msg_iov = &payload;
    message.msg_iovlen = 1;
    realSendMsg()(datagram.socket, &message, datagram.flags);
    close(datagram.socket);
  }

  std::uniform_real_distribution<double> jitter_;
  std::mt19937_64 random_;
  std::mutex mutex_;
  std::condition_variable wake_;
  std::priority_queue<Datagram, std::vector<Datagram>, std::greater<>> waiting_;
  bool sending_ = false;
};

// Never destroyed: its thread may still send while the process exits.
DelayLine* delayLine() {
  static DelayLine* const line = [] {
    const char* jitter_ms = std::getenv("LINELOC_TEST_SEND_JITTER_MS");
    const double value = jitter_ms != nullptr ? std::atof(jitter_ms) : 0.0;
    return value > 0.0 ? new DelayLine(value) : nullptr;
  }();
  return line;
}

__attribute__((destructor)) void sendWhatIsInFlight() {
  if (DelayLine* const line = delayLine()) {
    line->drain();
  }
}

bool isDatagramSocket(int socket) {
  int type = 0;
  socklen_t length = sizeof(type);
  return getsockopt(socket, SOL_SOCKET, SO_TYPE, &type, &length) == 0 && type == SOCK_DGRAM;
}

}  // namespace

extern "C" ssize_t sendmsg(int socket, const msghdr* message, int flags) {
  DelayLine* const line = delayLine();
  if (line == nullptr || message->msg_controllen != 0 || message->msg_namelen == 0 ||
      message->msg_namelen > sizeof(sockaddr_storage) || !isDatagramSocket(socket)) {
    return realSendMsg()(socket, message, flags);
  }
  Datagram datagram;
  datagram.flags = flags;
  std::memcpy(&datagram.destination, message->msg_name, message->msg_namelen);
  datagram.destination_length = message->msg_namelen;
  for (size_t i = 0; i < message->msg_iovlen; ++i) {
    const auto* base = static_cast<const char*>(message->msg_iov[i].iov_base);
    datagram.payload.insert(datagram.payload.end(), base, base + message->msg_iov[i].iov_len);
  }
  datagram.socket = dup(socket);
  if (datagram.socket < 0) {
    return realSendMsg()(socket, message, flags);
  }
  const auto sent = static_cast<ssize_t>(datagram.payload.size());
  line->push(std::move(datagram));
  return sent;
}
