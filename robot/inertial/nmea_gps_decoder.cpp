#include "robot/inertial/nmea_gps_decoder.h"

#include <cmath>
#include <stdexcept>

#include "common/nmea/nmea_sentence.h"

namespace lineloc {
namespace {

constexpr int64_t kNsPerDay = 86'400'000'000'000;

}  // namespace

int64_t stampNearest(int64_t time_of_day_ns, int64_t reference_ns) {
  const double days = std::round(static_cast<double>(reference_ns - time_of_day_ns) /
                                 static_cast<double>(kNsPerDay));
  return time_of_day_ns + static_cast<int64_t>(days) * kNsPerDay;
}

NmeaGpsDecoder::NmeaGpsDecoder(SiteProjection projection) : projection_(std::move(projection)) {}

std::optional<GpsFix> NmeaGpsDecoder::decode(std::string_view line, int64_t reference_stamp_ns) {
  const NmeaParseResult result = parseNmeaSentence(line);
  switch (result.status) {
    case NmeaStatus::kOk:
      break;
    case NmeaStatus::kNoFix:
      ++counters_.no_fix;
      return std::nullopt;
    case NmeaStatus::kBadChecksum:
      ++counters_.bad_checksum;
      return std::nullopt;
    case NmeaStatus::kUnsupportedType:
      ++counters_.unsupported;
      return std::nullopt;
    case NmeaStatus::kBadFraming:
    case NmeaStatus::kMalformedField:
      ++counters_.malformed;
      return std::nullopt;
  }
  if (const auto* rmc = std::get_if<RmcSentence>(&result.sentence)) {
    day_start_ns_ = rmc->utcStamp_ns() - rmc->time_of_day_ns;
    return std::nullopt;
  }
  const auto& gga = std::get<GgaSentence>(result.sentence);
  if (!day_start_ns_ && reference_stamp_ns == 0) {
    ++counters_.undated;
    return std::nullopt;
  }
  GpsFix fix;
  fix.stamp_ns = day_start_ns_ ? *day_start_ns_ + gga.time_of_day_ns
                               : stampNearest(gga.time_of_day_ns, reference_stamp_ns);
  try {
    fix.p_world_antenna =
        projection_.toSite({gga.latitude_deg, gga.longitude_deg, gga.altitude_msl_m});
  } catch (const std::domain_error&) {
    ++counters_.malformed;
    return std::nullopt;
  }
  ++counters_.fixes;
  return fix;
}

}  // namespace lineloc
