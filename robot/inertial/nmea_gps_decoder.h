// Turns NMEA 0183 sentences from a GPS receiver into DGPS fixes in the site
// frame: GGA gives the position (WGS84 latitude and longitude, height above
// mean sea level), projected with SiteProjection, and its uncertainty from the
// fix quality and HDOP (gnss_error_model.h); its UTC time
// of day is dated by the last RMC's date or, before any RMC, by the day
// nearest a reference time (the IMU clock). RMC gives the velocity over
// ground, when it holds both speed and course (a speed of zero needs no
// course): its course, a true bearing, turned into the grid by the meridian
// convergence at the sentence's position. Bad sentences are dropped and counted.
#pragma once

#include <optional>
#include <string_view>
#include <variant>

#include "common/geodesy/site_projection.h"
#include "robot/inertial/gnss_error_model.h"
#include "robot/inertial/inertial_navigator.h"

namespace lineloc {

struct NmeaCounters {
  int64_t fixes = 0;
  int64_t velocities = 0;
  int64_t no_fix = 0;
  int64_t bad_checksum = 0;
  int64_t malformed = 0;    // bad framing or fields, or outside the site CRS
  int64_t unsupported = 0;  // well-formed sentences other than GGA and RMC
  int64_t undated = 0;      // a GGA before any RMC and without a reference time
};

// What one sentence gives: a GGA's position, an RMC's velocity, or nothing.
using GpsReading = std::variant<std::monostate, GpsFix, GpsVelocity>;

class NmeaGpsDecoder {
 public:
  // Throws std::invalid_argument naming the value of `errors` that is not positive.
  explicit NmeaGpsDecoder(SiteProjection projection, const GnssErrorModel& errors = {});

  // The fix of a GGA sentence with a position, the velocity of an RMC with
  // one; nothing for anything else. `reference_stamp_ns` (0: none) dates GGA
  // times before the first RMC.
  GpsReading decode(std::string_view line, int64_t reference_stamp_ns = 0);

  const NmeaCounters& counters() const { return counters_; }
  const SiteProjection& projection() const { return projection_; }

 private:
  SiteProjection projection_;
  GnssErrorModel errors_;
  std::optional<int64_t> day_start_ns_;
  NmeaCounters counters_;
};

// A fix at `where` of GGA fix quality `quality` at `hdop`, in the site frame
// with its sigmas from `errors` (what a GGA sentence gives, and what gpsd
// reports of one). Throws std::domain_error where the projection does not
// reach.
GpsFix siteFix(int64_t stamp_ns, const GeodeticPosition& where, int quality, double hdop,
               const SiteProjection& projection, const GnssErrorModel& errors);

// The velocity over ground of `speed_mps` along the true course `course_deg`
// at `where`, in the site frame: v = s (sin beta, cos beta), beta the course
// turned into the grid by the meridian convergence there.
GpsVelocity siteVelocity(int64_t stamp_ns, const GeodeticPosition& where, double speed_mps,
                         double course_deg, const SiteProjection& projection);

// UTC nanoseconds of `time_of_day_ns` on the day that puts it nearest `reference_ns`.
int64_t stampNearest(int64_t time_of_day_ns, int64_t reference_ns);

}  // namespace lineloc
