#include "robot/input/gpsd_client.h"

#include <fmt/format.h>
#include <gps.h>

#include <cmath>
#include <stdexcept>

namespace lineloc {
namespace {

// gpsd's fix status as the GGA fix quality it stands for (gnss_error_model.h).
int ggaQuality(int status) {
  switch (status) {
    case STATUS_FIX:
      return static_cast<int>(GnssFixQuality::kGps);
    case STATUS_DGPS_FIX:
      return static_cast<int>(GnssFixQuality::kDgps);
    case STATUS_RTK_FIX:
      return static_cast<int>(GnssFixQuality::kRtkFixed);
    case STATUS_RTK_FLT:
      return static_cast<int>(GnssFixQuality::kRtkFloat);
    default:
      return static_cast<int>(GnssFixQuality::kNone);
  }
}

int64_t stampNs(const timespec_t& time) {
  return static_cast<int64_t>(time.tv_sec) * 1'000'000'000 + time.tv_nsec;
}

}  // namespace

GpsdClient::GpsdClient(const std::string& host, const std::string& port, SiteProjection projection,
                       const GnssErrorModel& errors)
    : where_(fmt::format("gpsd at {}:{}", host, port)),
      projection_(std::move(projection)),
      errors_(errors),
      data_(std::make_unique<gps_data_t>()) {
  validate(errors_);
  if (gps_open(host.c_str(), port.c_str(), data_.get()) != 0) {
    throw std::runtime_error(fmt::format("{}: cannot connect: {}", where_, gps_errstr(errno)));
  }
  if (gps_stream(data_.get(), WATCH_ENABLE | WATCH_JSON, nullptr) != 0) {
    gps_close(data_.get());
    throw std::runtime_error(fmt::format("{}: refuses to stream its reports", where_));
  }
}

GpsdClient::~GpsdClient() {
  gps_stream(data_.get(), WATCH_DISABLE, nullptr);
  gps_close(data_.get());
}

GpsdReports GpsdClient::read(int timeout_ms) {
  GpsdReports reports;
  int wait_us = timeout_ms * 1000;
  while (gps_waiting(data_.get(), wait_us)) {
    wait_us = 0;
    if (gps_read(data_.get(), nullptr, 0) < 0) {
      throw std::runtime_error(fmt::format("{}: connection lost", where_));
    }
    gps_data_t& data = *data_;
    if (std::isfinite(data.dop.hdop) && data.dop.hdop > 0.0) {
      hdop_ = data.dop.hdop;  // from its last SKY report
    }
    if ((data.set & MODE_SET) == 0) {
      continue;
    }
    const gps_fix_t& fix = data.fix;
    // A report without its altitude is no 3D fix, whatever its mode: gpsd
    // reports an epoch's RMC alone, before the GGA that holds its height and
    // fix quality, with the mode of the epoch before.
    if (fix.mode < MODE_3D || (data.set & LATLON_SET) == 0 || (data.set & TIME_SET) == 0 ||
        !std::isfinite(fix.latitude) || !std::isfinite(fix.longitude) ||
        !std::isfinite(fix.altMSL)) {
      ++reports.without_fix;
      continue;
    }
    const int64_t stamp_ns = stampNs(fix.time);
    const GeodeticPosition where{fix.latitude, fix.longitude, fix.altMSL};
    try {
      reports.readings.emplace_back(
          siteFix(stamp_ns, where, ggaQuality(fix.status), hdop_, projection_, errors_));
      if ((data.set & SPEED_SET) != 0 && std::isfinite(fix.speed) &&
          (fix.speed == 0.0 || ((data.set & TRACK_SET) != 0 && std::isfinite(fix.track)))) {
        reports.readings.emplace_back(siteVelocity(
            stamp_ns, where, fix.speed, fix.speed == 0.0 ? 0.0 : fix.track, projection_));
      }
    } catch (const std::domain_error&) {
      ++reports.without_fix;  // outside the site's CRS
    }
  }
  return reports;
}

}  // namespace lineloc
