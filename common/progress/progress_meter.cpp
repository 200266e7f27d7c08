#include "common/progress/progress_meter.h"

#include <fmt/format.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <ostream>

namespace lineloc {
namespace {

constexpr int kBarWidth = 30;

std::string formatDuration(double seconds) {
  const long rounded = std::lround(seconds);
  if (rounded < 60) {
    return fmt::format("{} s", rounded);
  }
  if (rounded < 3600) {
    return fmt::format("{} min {:02d} s", rounded / 60, rounded % 60);
  }
  return fmt::format("{} h {:02d} min", rounded / 3600, (rounded % 3600) / 60);
}

std::string formatRate(double per_s) {
  return per_s >= 10.0 ? fmt::format("{:.0f}/s", per_s) : fmt::format("{:.2g}/s", per_s);
}

}  // namespace

ProgressMeter::ProgressMeter(std::string what, std::string unit, std::ostream& out, Style style,
                             double log_period_s, Clock clock)
    : what_(std::move(what)),
      unit_(std::move(unit)),
      out_(out),
      style_(style),
      period_s_(style == Style::kTerminal ? kTerminalPeriod_s : log_period_s),
      clock_(std::move(clock)),
      start_s_(clock_()),
      last_print_s_(start_s_) {}

ProgressMeter::Style ProgressMeter::styleOf(int file_descriptor) {
  return isatty(file_descriptor) != 0 ? Style::kTerminal : Style::kLog;
}

ProgressMeter::Clock ProgressMeter::steadyClock() {
  return [] {
    return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch())
        .count();
  };
}

void ProgressMeter::update(size_t done, size_t total) {
  if (finished_) {
    return;
  }
  const double now_s = clock_();
  const bool finished = done >= total;
  if (!finished && now_s - last_print_s_ < period_s_) {
    return;
  }
  last_print_s_ = now_s;
  finished_ = finished;
  print(done, total, now_s - start_s_, finished);
}

ProgressCallback ProgressMeter::callback() {
  return [this](size_t done, size_t total) { update(done, total); };
}

void ProgressMeter::print(size_t done, size_t total, double elapsed_s, bool finished) {
  const double rate_per_s = elapsed_s > 0.0 ? done / elapsed_s : 0.0;
  std::string timing;
  if (finished) {
    timing = fmt::format("{} in {}", formatRate(rate_per_s), formatDuration(elapsed_s));
  } else if (rate_per_s > 0.0) {
    timing = fmt::format("{}, {} left", formatRate(rate_per_s),
                         formatDuration((total - done) / rate_per_s));
  }
  if (style_ == Style::kLog) {
    const int percent = total > 0 ? static_cast<int>(100 * done / total) : 100;
    out_ << fmt::format("{}: {}/{} {} ({} %){}{}\n", what_, done, total, unit_, percent,
                        timing.empty() ? "" : ", ", timing)
         << std::flush;
    return;
  }
  const int filled =
      total > 0 ? static_cast<int>(kBarWidth * std::min(done, total) / total) : kBarWidth;
  out_ << fmt::format("\r{} [{}{}] {}/{} {}  {}\033[K", what_, std::string(filled, '#'),
                      std::string(kBarWidth - filled, '.'), done, total, unit_, timing)
       << (finished ? "\n" : "") << std::flush;
}

}  // namespace lineloc
