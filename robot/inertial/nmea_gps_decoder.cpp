#include "robot/inertial/nmea_gps_decoder.h"

#include <cmath>
#include <stdexcept>

#include "common/nmea/nmea_sentence.h"

namespace lineloc {
namespace {

constexpr int64_t kNsPerDay = 86'400'000'000'000;
constexpr double kMetresPerSecondPerKnot = 1852.0 / 3600.0;

// The velocity of an RMC with speed and course (a speed of zero needs none);
// throws std::domain_error where the projection does not reach.
std::optional<GpsVelocity> velocityOf(const RmcSentence& rmc, const SiteProjection& projection) {
  if (!rmc.speed_knots || !(rmc.course_deg || *rmc.speed_knots == 0.0)) {
    return std::nullopt;
  }
  return siteVelocity(rmc.utcStamp_ns(), {rmc.latitude_deg, rmc.longitude_deg, 0.0},
                      *rmc.speed_knots * kMetresPerSecondPerKnot, rmc.course_deg.value_or(0.0),
                      projection);
}

}  // namespace

GpsFix siteFix(int64_t stamp_ns, const GeodeticPosition& where, int quality, double hdop,
               const SiteProjection& projection, const GnssErrorModel& errors) {
  GpsFix fix;
  fix.stamp_ns = stamp_ns;
  fix.p_world_antenna = projection.toSite(where);
  if (const std::optional<GnssSigmas> sigmas = gnssSigmas(quality, hdop, errors)) {
    fix.horizontal_sigma_m = sigmas->horizontal_m;
    fix.vertical_sigma_m = sigmas->vertical_m;
  }
  return fix;
}

GpsVelocity siteVelocity(int64_t stamp_ns, const GeodeticPosition& where, double speed_mps,
                         double course_deg, const SiteProjection& projection) {
  // v = s (sin beta, cos beta), beta the grid bearing = true course + grid
  // bearing of true north.
  const double grid_bearing_rad =
      course_deg * M_PI / 180.0 + projection.gridBearingOfTrueNorth_rad(where);
  return GpsVelocity{stamp_ns,
                     speed_mps * Eigen::Vector2d(std::sin(grid_bearing_rad),
                                                 std::cos(grid_bearing_rad))};
}

int64_t stampNearest(int64_t time_of_day_ns, int64_t reference_ns) {
  const double days = std::round(static_cast<double>(reference_ns - time_of_day_ns) /
                                 static_cast<double>(kNsPerDay));
  return time_of_day_ns + static_cast<int64_t>(days) * kNsPerDay;
}

NmeaGpsDecoder::NmeaGpsDecoder(SiteProjection projection, const GnssErrorModel& errors)
    : projection_(std::move(projection)), errors_(errors) {
  validate(errors_);
}

GpsReading NmeaGpsDecoder::decode(std::string_view line, int64_t reference_stamp_ns) {
  const NmeaParseResult result = parseNmeaSentence(line);
  switch (result.status) {
    case NmeaStatus::kOk:
      break;
    case NmeaStatus::kNoFix:
      ++counters_.no_fix;
      return {};
    case NmeaStatus::kBadChecksum:
      ++counters_.bad_checksum;
      return {};
    case NmeaStatus::kUnsupportedType:
      ++counters_.unsupported;
      return {};
    case NmeaStatus::kBadFraming:
    case NmeaStatus::kMalformedField:
      ++counters_.malformed;
      return {};
  }
  if (const auto* rmc = std::get_if<RmcSentence>(&result.sentence)) {
    day_start_ns_ = rmc->utcStamp_ns() - rmc->time_of_day_ns;
    try {
      const std::optional<GpsVelocity> velocity = velocityOf(*rmc, projection_);
      if (!velocity) {
        return {};
      }
      ++counters_.velocities;
      return *velocity;
    } catch (const std::domain_error&) {
      ++counters_.malformed;
      return {};
    }
  }
  const auto& gga = std::get<GgaSentence>(result.sentence);
  if (!day_start_ns_ && reference_stamp_ns == 0) {
    ++counters_.undated;
    return {};
  }
  const int64_t stamp_ns = day_start_ns_ ? *day_start_ns_ + gga.time_of_day_ns
                                         : stampNearest(gga.time_of_day_ns, reference_stamp_ns);
  GpsFix fix;
  try {
    fix = siteFix(stamp_ns, {gga.latitude_deg, gga.longitude_deg, gga.altitude_msl_m},
                  gga.fix_quality, gga.hdop, projection_, errors_);
  } catch (const std::domain_error&) {
    ++counters_.malformed;
    return {};
  }
  ++counters_.fixes;
  return fix;
}

}  // namespace lineloc
