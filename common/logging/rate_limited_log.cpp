#include "common/logging/rate_limited_log.h"

#include <stdexcept>
#include <utility>

#include "common/time/clock.h"

namespace lineloc {

RateLimitedLog::RateLimitedLog(std::string what, int max_lines_per_interval, double interval_s,
                               spdlog::level::level_enum level,
                               std::shared_ptr<spdlog::logger> logger)
    : what_(std::move(what)),
      max_lines_per_interval_(max_lines_per_interval),
      interval_ns_(static_cast<int64_t>(interval_s * 1e9)),
      level_(level),
      logger_(logger ? std::move(logger) : spdlog::default_logger()) {
  if (max_lines_per_interval_ < 1 || !(interval_s > 0.0)) {
    throw std::invalid_argument(
        what_ + ": a rate-limited log needs at least one line per positive interval");
  }
}

void RateLimitedLog::advance(int64_t now_ns) {
  if (!started_) {
    started_ = true;
    interval_start_ns_ = now_ns;
    return;
  }
  if (now_ns - interval_start_ns_ < interval_ns_) {
    return;
  }
  if (unreported_ > 0) {
    logger_->log(level_, "{}: {} more not logged in the last {:.1f} s", what_, unreported_,
                 (now_ns - interval_start_ns_) * 1e-9);
    unreported_ = 0;
  }
  interval_start_ns_ = now_ns;
  lines_this_interval_ = 0;
}

void RateLimitedLog::log(int64_t now_ns, const std::string& line) {
  const std::lock_guard<std::mutex> lock(mutex_);
  advance(now_ns);
  if (lines_this_interval_ < max_lines_per_interval_) {
    ++lines_this_interval_;
    ++logged_;
    logger_->log(level_, "{}", line);
    return;
  }
  ++unreported_;
  ++suppressed_;
}

void RateLimitedLog::log(const std::string& line) {
  log(steadyClockNs(), line);
}

void RateLimitedLog::flush(int64_t now_ns) {
  const std::lock_guard<std::mutex> lock(mutex_);
  if (started_) {
    advance(now_ns);
  }
}

uint64_t RateLimitedLog::logged() const {
  const std::lock_guard<std::mutex> lock(mutex_);
  return logged_;
}

uint64_t RateLimitedLog::suppressed() const {
  const std::lock_guard<std::mutex> lock(mutex_);
  return suppressed_;
}

}  // namespace lineloc
