#include "common/geodesy/site_projection.h"

#include <fmt/format.h>
#include <proj.h>

#include <GeographicLib/UTMUPS.hpp>
#include <charconv>
#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string_view>

namespace lineloc {
namespace {

constexpr double kDegToRad = M_PI / 180.0;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
// Northward step for the numerical convergence: 1e-5 deg = 1.1 m, small enough
// that the grid's curvature over it changes the bearing by < 1e-7 rad.
constexpr double kConvergenceStep_deg = 1e-5;
constexpr int kEpsgUtmNorthBase = 32600;
constexpr int kEpsgUtmSouthBase = 32700;
constexpr std::string_view kUtmPrefix = "UTM:";
constexpr std::string_view kEpsgPrefix = "EPSG:";

struct EastingNorthing {
  double easting;
  double northing;
};

}  // namespace

// Forward and inverse horizontal projection of one CRS.
class SiteProjectionBackend {
 public:
  virtual ~SiteProjectionBackend() = default;
  virtual EastingNorthing forward(double latitude_deg, double longitude_deg) const = 0;
  virtual GeodeticPosition inverse(double easting, double northing) const = 0;
  virtual double gridBearingOfTrueNorth_rad(double latitude_deg, double longitude_deg) const = 0;
};

namespace {

class UtmBackend final : public SiteProjectionBackend {
 public:
  UtmBackend(int zone, bool north) : zone_(zone), north_(north) {}

  EastingNorthing forward(double latitude_deg, double longitude_deg) const override {
    int zone = 0;
    bool north = false;
    double gamma_deg = 0.0;
    double scale = 0.0;
    EastingNorthing en{};
    try {
      GeographicLib::UTMUPS::Forward(latitude_deg, longitude_deg, zone, north, en.easting,
                                     en.northing, gamma_deg, scale, zone_);
    } catch (const GeographicLib::GeographicErr&) {
      return {kNaN, kNaN};
    }
    return shiftHemisphere(en, north);
  }

  GeodeticPosition inverse(double easting, double northing) const override {
    GeodeticPosition position;
    try {
      GeographicLib::UTMUPS::Reverse(zone_, north_, easting, northing, position.latitude_deg,
                                     position.longitude_deg);
    } catch (const GeographicLib::GeographicErr&) {
      position.latitude_deg = kNaN;
    }
    return position;
  }

  double gridBearingOfTrueNorth_rad(double latitude_deg, double longitude_deg) const override {
    int zone = 0;
    bool north = false;
    double easting = 0.0;
    double northing = 0.0;
    double gamma_deg = 0.0;
    double scale = 0.0;
    try {
      GeographicLib::UTMUPS::Forward(latitude_deg, longitude_deg, zone, north, easting, northing,
                                     gamma_deg, scale, zone_);
    } catch (const GeographicLib::GeographicErr&) {
      throw std::domain_error(
          fmt::format("({}, {}) deg is outside UTM zone {}", latitude_deg, longitude_deg, zone_));
    }
    return -gamma_deg * kDegToRad;
  }

 private:
  // A point across the equator is expressed in this zone's hemisphere convention.
  EastingNorthing shiftHemisphere(EastingNorthing en, bool north) const {
    if (north != north_) {
      en.northing +=
          north_ ? -GeographicLib::UTMUPS::UTMShift() : GeographicLib::UTMUPS::UTMShift();
    }
    return en;
  }

  int zone_;
  bool north_;
};

struct ProjDeleter {
  void operator()(PJ* pj) const { proj_destroy(pj); }
  void operator()(PJ_CONTEXT* context) const { proj_context_destroy(context); }
};
using ProjPtr = std::unique_ptr<PJ, ProjDeleter>;
using ProjContextPtr = std::unique_ptr<PJ_CONTEXT, ProjDeleter>;

class ProjBackend final : public SiteProjectionBackend {
 public:
  explicit ProjBackend(const std::string& crs) : context_(proj_context_create()) {
    // Failures are reported through the exceptions below, not PROJ's stderr log.
    proj_log_level(context_.get(), PJ_LOG_NONE);
    ProjPtr target(proj_create(context_.get(), crs.c_str()));
    if (!target) {
      throw std::invalid_argument(fmt::format("CRS '{}' is unknown to PROJ: {}", crs, lastError()));
    }
    if (proj_get_type(target.get()) == PJ_TYPE_COMPOUND_CRS) {
      target.reset(proj_crs_get_sub_crs(context_.get(), target.get(), 0));
    }
    if (!target || proj_get_type(target.get()) != PJ_TYPE_PROJECTED_CRS) {
      throw std::invalid_argument(fmt::format("CRS '{}' is not a projected CRS", crs));
    }
    const ProjPtr wgs84(proj_create(context_.get(), "EPSG:4326"));
    const ProjPtr transform(proj_create_crs_to_crs_from_pj(context_.get(), wgs84.get(),
                                                           target.get(), nullptr, nullptr));
    if (!transform) {
      throw std::invalid_argument(
          fmt::format("PROJ has no transformation from WGS84 to '{}': {}", crs, lastError()));
    }
    transform_.reset(proj_normalize_for_visualization(context_.get(), transform.get()));
    if (!transform_) {
      throw std::invalid_argument(fmt::format("cannot normalise the axes of '{}'", crs));
    }
  }

  EastingNorthing forward(double latitude_deg, double longitude_deg) const override {
    const PJ_COORD xy =
        proj_trans(transform_.get(), PJ_FWD, proj_coord(longitude_deg, latitude_deg, 0.0, 0.0));
    return {xy.xy.x, xy.xy.y};
  }

  GeodeticPosition inverse(double easting, double northing) const override {
    const PJ_COORD lonlat =
        proj_trans(transform_.get(), PJ_INV, proj_coord(easting, northing, 0.0, 0.0));
    GeodeticPosition position;
    position.latitude_deg = lonlat.lp.phi;
    position.longitude_deg = lonlat.lp.lam;
    return position;
  }

  double gridBearingOfTrueNorth_rad(double latitude_deg, double longitude_deg) const override {
    const EastingNorthing here = forward(latitude_deg, longitude_deg);
    const EastingNorthing north = forward(latitude_deg + kConvergenceStep_deg, longitude_deg);
    return std::atan2(north.easting - here.easting, north.northing - here.northing);
  }

 private:
  std::string lastError() const {
    return proj_context_errno_string(context_.get(), proj_context_errno(context_.get()));
  }

  ProjContextPtr context_;
  ProjPtr transform_;
};

// The decimal number that is the whole of `text`, if it is one of at most 6 digits.
std::optional<int> parseCode(std::string_view text) {
  int value = 0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (text.empty() || text.size() > 6 || error != std::errc() || end != text.data() + text.size() ||
      text.front() == '-') {
    return std::nullopt;
  }
  return value;
}

std::unique_ptr<SiteProjectionBackend> makeBackend(const std::string& crs) {
  const std::string_view text(crs);
  if (text.starts_with(kUtmPrefix) && text.size() > kUtmPrefix.size() + 1) {
    const char hemisphere = text.back();
    const auto zone =
        parseCode(text.substr(kUtmPrefix.size(), text.size() - kUtmPrefix.size() - 1));
    if (!zone || (hemisphere != 'N' && hemisphere != 'S') ||
        *zone < GeographicLib::UTMUPS::MINUTMZONE || *zone > GeographicLib::UTMUPS::MAXUTMZONE) {
      throw std::invalid_argument(
          fmt::format("CRS '{}': expected UTM:<zone 1-60><N|S>, e.g. UTM:31N", crs));
    }
    return std::make_unique<UtmBackend>(*zone, hemisphere == 'N');
  }
  const auto code =
      text.starts_with(kEpsgPrefix) ? parseCode(text.substr(kEpsgPrefix.size())) : std::nullopt;
  if (!code) {
    throw std::invalid_argument(
        fmt::format("CRS '{}' is neither 'UTM:<zone><N|S>' nor 'EPSG:<code>'", crs));
  }
  for (const int base : {kEpsgUtmNorthBase, kEpsgUtmSouthBase}) {
    if (*code > base && *code <= base + GeographicLib::UTMUPS::MAXUTMZONE) {
      return std::make_unique<UtmBackend>(*code - base, base == kEpsgUtmNorthBase);
    }
  }
  return std::make_unique<ProjBackend>(crs);
}

}  // namespace

SiteProjection::SiteProjection(const std::string& crs, const Eigen::Vector3d& origin)
    : crs_(crs), origin_(origin), backend_(makeBackend(crs)) {
  if (!origin.allFinite()) {
    throw std::invalid_argument(fmt::format("site origin of CRS '{}' is not finite", crs));
  }
}

SiteProjection::~SiteProjection() = default;
SiteProjection::SiteProjection(SiteProjection&&) noexcept = default;
SiteProjection& SiteProjection::operator=(SiteProjection&&) noexcept = default;

Eigen::Vector3d SiteProjection::toSite(const GeodeticPosition& position) const {
  const EastingNorthing en = backend_->forward(position.latitude_deg, position.longitude_deg);
  const Eigen::Vector3d p_site =
      Eigen::Vector3d(en.easting, en.northing, position.height_msl_m) - origin_;
  if (!p_site.allFinite()) {
    throw std::domain_error(fmt::format("({}, {}) deg is outside the domain of CRS '{}'",
                                        position.latitude_deg, position.longitude_deg, crs_));
  }
  return p_site;
}

GeodeticPosition SiteProjection::toGeodetic(const Eigen::Vector3d& p_site) const {
  const Eigen::Vector3d projected = p_site + origin_;
  GeodeticPosition position = backend_->inverse(projected.x(), projected.y());
  if (!std::isfinite(position.latitude_deg) || !std::isfinite(position.longitude_deg)) {
    throw std::domain_error(fmt::format("site point ({}, {}) is outside the domain of CRS '{}'",
                                        p_site.x(), p_site.y(), crs_));
  }
  position.height_msl_m = projected.z();
  return position;
}

double SiteProjection::gridBearingOfTrueNorth_rad(const GeodeticPosition& position) const {
  return backend_->gridBearingOfTrueNorth_rad(position.latitude_deg, position.longitude_deg);
}

}  // namespace lineloc
