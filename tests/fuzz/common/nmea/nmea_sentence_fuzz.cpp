// Feeds arbitrary bytes to the NMEA parser; a sentence that parses must format
// back to one that parses to the same status.
#include <cstdint>
#include <cstdlib>
#include <string_view>

#include "common/nmea/nmea_sentence.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  const lineloc::NmeaParseResult result = lineloc::parseNmeaSentence(text);
  if (result.status != lineloc::NmeaStatus::kOk) {
    return 0;
  }
  const std::string formatted =
      std::holds_alternative<lineloc::GgaSentence>(result.sentence)
          ? lineloc::formatGga(std::get<lineloc::GgaSentence>(result.sentence))
          : lineloc::formatRmc(std::get<lineloc::RmcSentence>(result.sentence));
  if (lineloc::parseNmeaSentence(formatted).status != lineloc::NmeaStatus::kOk) {
    std::abort();
  }
  return 0;
}
