// Progress of long work (rendering a drive, loading a city model) for the
// person waiting on it. With `done` of `total` items after t seconds, the rate
// is r = done / t and the time left (total - done) / r.
//
// On a terminal, one line redrawn in place at most every kTerminalPeriod_s:
//   loading denhaag.city.json [######........] 1200/2497 buildings  310/s, 4 s left
// In a log (output redirected to a file), a plain line every `log_period_s`:
//   loading denhaag.city.json: 1200/2497 buildings (48 %), 310/s, 4 s left
// Both print the finished work once, with the rate and the time it took.
#pragma once

#include <cstddef>
#include <functional>
#include <iosfwd>
#include <string>

namespace lineloc {

// `progress(done, total)`: `done` of `total` items finished.
using ProgressCallback = std::function<void(size_t done, size_t total)>;

class ProgressMeter {
 public:
  enum class Style { kTerminal, kLog };
  // Seconds on a monotonic clock.
  using Clock = std::function<double()>;

  static constexpr double kTerminalPeriod_s = 0.1;

  // `what` names the work, `unit` its items in the plural ("buildings").
  ProgressMeter(std::string what, std::string unit, std::ostream& out, Style style,
                double log_period_s = 10.0, Clock clock = steadyClock());

  // kTerminal when the file descriptor is a terminal, kLog otherwise.
  static Style styleOf(int file_descriptor);
  static Clock steadyClock();

  // Reports `done` of `total` when a line is due or the work is finished.
  void update(size_t done, size_t total);
  // update() as a ProgressCallback; the meter must outlive it.
  ProgressCallback callback();

 private:
  void print(size_t done, size_t total, double elapsed_s, bool finished);

  std::string what_;
  std::string unit_;
  std::ostream& out_;
  Style style_;
  double period_s_;
  Clock clock_;
  double start_s_;
  double last_print_s_;
  bool finished_ = false;
};

}  // namespace lineloc
