// UTC date and time as ISO 8601 text, "2026-05-21T08:30:00Z" (an optional
// fraction of a second after the seconds), <-> Unix time stamps in
// nanoseconds (clock.h). Leap seconds do not exist in Unix time; "...:60Z" is
// refused.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

namespace lineloc {

// Throws std::invalid_argument naming the text and the first character that
// does not fit the form, or the field out of range (month 13, February 30).
int64_t parseUtcTime_ns(std::string_view text);

// "YYYY-MM-DDTHH:MM:SS.fffffffffZ", the fraction omitted when zero.
std::string formatUtcTime(int64_t unix_ns);

}  // namespace lineloc
