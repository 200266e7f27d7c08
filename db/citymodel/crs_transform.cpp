#include "db/citymodel/crs_transform.h"

#include <fmt/format.h>
#include <proj.h>

#include <stdexcept>

namespace lineloc::citymodel {

struct CrsTransform::Proj {
  PJ_CONTEXT* context = nullptr;
  PJ* transformation = nullptr;

  ~Proj() {
    if (transformation != nullptr) {
      proj_destroy(transformation);
    }
    if (context != nullptr) {
      proj_context_destroy(context);
    }
  }
};

CrsTransform::CrsTransform(int source_epsg, int target_epsg)
    : source_epsg_(source_epsg), target_epsg_(target_epsg), proj_(std::make_unique<Proj>()) {
  if (isIdentity()) {
    return;
  }
  proj_->context = proj_context_create();
  proj_log_level(proj_->context, PJ_LOG_NONE);
  const std::string source = fmt::format("EPSG:{}", source_epsg);
  const std::string target = fmt::format("EPSG:{}", target_epsg);
  PJ* raw = proj_create_crs_to_crs(proj_->context, source.c_str(), target.c_str(), nullptr);
  if (raw == nullptr) {
    throw std::invalid_argument(
        fmt::format("no transformation from {} to {} known to PROJ: {}", source, target,
                    proj_context_errno_string(proj_->context, proj_context_errno(proj_->context))));
  }
  proj_->transformation = proj_normalize_for_visualization(proj_->context, raw);
  proj_destroy(raw);
  if (proj_->transformation == nullptr) {
    throw std::invalid_argument(
        fmt::format("cannot normalise the axis order of {} -> {}", source, target));
  }
}

CrsTransform::~CrsTransform() = default;

Eigen::Vector3d CrsTransform::apply(const Eigen::Vector3d& point) const {
  if (isIdentity()) {
    return point;
  }
  const PJ_COORD result =
      proj_trans(proj_->transformation, PJ_FWD, proj_coord(point.x(), point.y(), point.z(), 0.0));
  const Eigen::Vector3d transformed(result.xyz.x, result.xyz.y, result.xyz.z);
  if (!transformed.allFinite() || std::abs(transformed.x()) == HUGE_VAL) {
    throw std::domain_error(
        fmt::format("({}, {}, {}) cannot be transformed from EPSG:{} to EPSG:{}", point.x(),
                    point.y(), point.z(), source_epsg_, target_epsg_));
  }
  return transformed;
}

void CrsTransform::apply(CityModel& model, const std::string& source,
                         InvalidObjectPolicy policy) const {
  model.epsg = target_epsg_;
  if (isIdentity()) {
    return;
  }
  std::vector<Building> transformed;
  transformed.reserve(model.buildings.size());
  for (Building& building : model.buildings) {
    try {
      for (Face& face : building.faces) {
        for (auto& ring : face.rings) {
          for (Eigen::Vector3d& point : ring) {
            point = apply(point);
          }
        }
      }
      transformed.push_back(std::move(building));
    } catch (const std::domain_error& error) {
      handleInvalidObject(ModelError(source, building.id, "outside the CRS", error.what()), policy,
                          model.skipped);
    }
  }
  model.buildings = std::move(transformed);
  try {
    for (TerrainTriangle& triangle : model.terrain) {
      for (Eigen::Vector3d& point : triangle) {
        point = apply(point);
      }
    }
  } catch (const std::domain_error& error) {
    handleInvalidObject(ModelError(source, "terrain", "outside the CRS", error.what()), policy,
                        model.skipped);
    model.terrain.clear();
  }
}

}  // namespace lineloc::citymodel
