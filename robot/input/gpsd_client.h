// GNSS fixes from gpsd, the GPS service daemon, through libgps: each report
// of a 3D fix (a TPV) becomes a fix in the site frame, with its sigmas from
// the fix's status (autonomous, DGPS, RTK fixed or float) and the HDOP of
// gpsd's last SKY report (gnss_error_model.h; none before the first, or from
// a receiver that sends no satellites' view), and, where it holds speed and
// track, a velocity over ground. Each is stamped with the fix's UTC time, the
// receiver's clock.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "common/geodesy/site_projection.h"
#include "robot/inertial/gnss_error_model.h"
#include "robot/inertial/nmea_gps_decoder.h"

struct gps_data_t;

namespace lineloc {

// What gpsd reported: fixes and velocities, and the reports that held no fix.
struct GpsdReports {
  std::vector<GpsReading> readings;
  int without_fix = 0;
};

class GpsdClient {
 public:
  // Connects to gpsd at host:port and asks it to stream its reports. Throws
  // std::runtime_error naming host:port when gpsd cannot be reached.
  GpsdClient(const std::string& host, const std::string& port, SiteProjection projection,
             const GnssErrorModel& errors);
  ~GpsdClient();
  GpsdClient(const GpsdClient&) = delete;
  GpsdClient& operator=(const GpsdClient&) = delete;

  // The reports that come within `timeout_ms`. Throws std::runtime_error
  // naming gpsd when the connection is lost.
  GpsdReports read(int timeout_ms);

 private:
  std::string where_;
  SiteProjection projection_;
  GnssErrorModel errors_;
  std::unique_ptr<gps_data_t> data_;
  double hdop_ = 0.0;
};

}  // namespace lineloc
