#include "common/time/utc_time.h"

#include <fmt/format.h>

#include <chrono>
#include <stdexcept>

namespace lineloc {
namespace {

constexpr int64_t kNsPerSecond = 1'000'000'000;

// Reads the text field by field, naming the first offence.
class UtcTimeReader {
 public:
  explicit UtcTimeReader(std::string_view text) : text_(text) {}

  int number(int digits, const char* field, int min, int max) {
    int value = 0;
    for (int i = 0; i < digits; ++i) {
      const char c = at(position_);
      if (c < '0' || c > '9') {
        fail(fmt::format("expected a digit of the {}", field));
      }
      value = value * 10 + (c - '0');
      ++position_;
    }
    if (value < min || value > max) {
      fail(fmt::format("{} {} is outside {}..{}", field, value, min, max), position_ - digits);
    }
    return value;
  }

  void literal(char expected) {
    if (at(position_) != expected) {
      fail(fmt::format("expected '{}'", expected));
    }
    ++position_;
  }

  // ".ddd" up to nanoseconds, or nothing.
  int64_t fraction_ns() {
    if (at(position_) != '.') {
      return 0;
    }
    ++position_;
    int64_t ns = 0;
    int digits = 0;
    for (char c = at(position_); c >= '0' && c <= '9'; c = at(++position_)) {
      if (++digits > 9) {
        fail("more than nine digits of a second");
      }
      ns = ns * 10 + (c - '0');
    }
    if (digits == 0) {
      fail("expected a digit after '.'");
    }
    for (; digits < 9; ++digits) {
      ns *= 10;
    }
    return ns;
  }

  void end() {
    if (position_ != text_.size()) {
      fail("expected the end of the time after 'Z'");
    }
  }

  [[noreturn]] void fail(const std::string& what) const { fail(what, position_); }

  [[noreturn]] void fail(const std::string& what, size_t position) const {
    throw std::invalid_argument(
        fmt::format("UTC time '{}' at character {}: {} (form: 2026-05-21T08:30:00Z)", text_,
                    position + 1, what));
  }

 private:
  char at(size_t position) const { return position < text_.size() ? text_[position] : '\0'; }

  std::string_view text_;
  size_t position_ = 0;
};

}  // namespace

int64_t parseUtcTime_ns(std::string_view text) {
  UtcTimeReader reader(text);
  const int year = reader.number(4, "year", 1970, 2261);
  reader.literal('-');
  const int month = reader.number(2, "month", 1, 12);
  reader.literal('-');
  const int day = reader.number(2, "day", 1, 31);
  reader.literal('T');
  const int hour = reader.number(2, "hour", 0, 23);
  reader.literal(':');
  const int minute = reader.number(2, "minute", 0, 59);
  reader.literal(':');
  const int second = reader.number(2, "second", 0, 59);
  const int64_t fraction_ns = reader.fraction_ns();
  reader.literal('Z');
  reader.end();
  const std::chrono::year_month_day date{std::chrono::year(year),
                                         std::chrono::month(static_cast<unsigned>(month)),
                                         std::chrono::day(static_cast<unsigned>(day))};
  if (!date.ok()) {
    reader.fail(fmt::format("{:04}-{:02} has no day {}", year, month, day), 8);
  }
  const int64_t days = std::chrono::sys_days(date).time_since_epoch().count();
  const int64_t seconds = ((days * 24 + hour) * 60 + minute) * 60 + second;
  return seconds * kNsPerSecond + fraction_ns;
}

std::string formatUtcTime(int64_t unix_ns) {
  const std::chrono::sys_time<std::chrono::nanoseconds> time{std::chrono::nanoseconds(unix_ns)};
  const std::chrono::sys_days day = std::chrono::floor<std::chrono::days>(time);
  const std::chrono::year_month_day date(day);
  const std::chrono::hh_mm_ss<std::chrono::nanoseconds> clock(time - day);
  const std::string whole =
      fmt::format("{:04}-{:02}-{:02}T{:02}:{:02}:{:02}", static_cast<int>(date.year()),
                  static_cast<unsigned>(date.month()), static_cast<unsigned>(date.day()),
                  clock.hours().count(), clock.minutes().count(), clock.seconds().count());
  const int64_t fraction_ns = clock.subseconds().count();
  return fraction_ns == 0 ? whole + "Z" : fmt::format("{}.{:09}Z", whole, fraction_ns);
}

}  // namespace lineloc
