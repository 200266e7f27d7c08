// Fuzz target: ISO 8601 UTC times (the simulator's --start-utc).
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string_view>

#include "common/time/utc_time.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    const int64_t stamp_ns = lineloc::parseUtcTime_ns(text);
    if (stamp_ns < 0 || lineloc::parseUtcTime_ns(lineloc::formatUtcTime(stamp_ns)) != stamp_ns) {
      __builtin_trap();  // accepted a time that does not survive formatting
    }
  } catch (const std::invalid_argument&) {
  }
  return 0;
}
