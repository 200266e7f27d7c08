// A log of events that outside input can cause at any rate (a dropped
// message, a skipped frame, a failure each frame meets): at most
// max_lines_per_interval of them are logged per interval, at one level; the
// rest are counted and summarised as one line, "<what>: N more not logged in
// the last S s", when the interval they fell in has ended and the next event
// comes or flush() is called. Every event is either logged or counted in
// exactly one summary. Thread-safe.
#pragma once

#include <spdlog/spdlog.h>

#include <cstdint>
#include <memory>
#include <mutex>
#include <string>

namespace lineloc {

class RateLimitedLog {
 public:
  // `what` names the events in summaries; `logger` defaults to spdlog's
  // default logger.
  RateLimitedLog(std::string what, int max_lines_per_interval, double interval_s,
                 spdlog::level::level_enum level = spdlog::level::warn,
                 std::shared_ptr<spdlog::logger> logger = nullptr);

  // Logs `line` at `now_ns` (steady clock), unless this interval's lines are
  // spent.
  void log(int64_t now_ns, const std::string& line);
  // The same at the steady clock's time.
  void log(const std::string& line);

  // Logs the summary of the events not logged, once their interval has ended.
  void flush(int64_t now_ns);

  // Events logged, and events not logged, since construction.
  uint64_t logged() const;
  uint64_t suppressed() const;

 private:
  // Starts a new interval at `now_ns` when the current one has ended, first
  // logging its summary. Called with mutex_ held.
  void advance(int64_t now_ns);

  const std::string what_;
  const int max_lines_per_interval_;
  const int64_t interval_ns_;
  const spdlog::level::level_enum level_;
  const std::shared_ptr<spdlog::logger> logger_;
  mutable std::mutex mutex_;
  bool started_ = false;
  int64_t interval_start_ns_ = 0;
  int lines_this_interval_ = 0;
  uint64_t unreported_ = 0;
  uint64_t logged_ = 0;
  uint64_t suppressed_ = 0;
};

}  // namespace lineloc
