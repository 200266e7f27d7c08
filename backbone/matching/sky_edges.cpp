#include "backbone/matching/sky_edges.h"

#include <algorithm>
#include <cmath>

namespace lineloc {
namespace {

// The unit ray `direction` turned by `angle_rad` towards the ground, in its
// vertical plane.
Eigen::Vector3d lowered(const Eigen::Vector3d& direction, double angle_rad) {
  const Eigen::Vector3d up = (Eigen::Vector3d::UnitZ() - direction.z() * direction).normalized();
  return std::cos(angle_rad) * direction - std::sin(angle_rad) * up;
}

enum class Sky { kNone, kOpen, kClear };

// Classifies the image points seen from one pose.
class SkyClassifier {
 public:
  SkyClassifier(const Eigen::Isometry3d& T_world_camera, const PinholeCamera& camera,
                const OcclusionScene& scene, const SkyEdgeOptions& options)
      : ray_from_pixel_(T_world_camera.linear() * camera.K().inverse()),
        origin_(T_world_camera.translation()),
        scene_(scene),
        min_rise_(std::sin(options.min_elevation_rad)),
        margin_rad_(options.margin_px / camera.fx),
        clear_margin_rad_(options.clear_margin_rad),
        reach_m_(options.reach_m) {}

  Sky at(const Eigen::Vector2d& pixel) const {
    const Eigen::Vector3d direction = (ray_from_pixel_ * pixel.homogeneous()).normalized();
    if (direction.z() < min_rise_ || meetsFace(direction) ||
        meetsFace(lowered(direction, margin_rad_))) {
      return Sky::kNone;
    }
    return meetsFace(lowered(direction, clear_margin_rad_)) ? Sky::kOpen : Sky::kClear;
  }

 private:
  bool meetsFace(const Eigen::Vector3d& direction) const {
    return scene_.blocked(origin_, origin_ + reach_m_ * direction, 0.0);
  }

  Eigen::Matrix3d ray_from_pixel_;
  Eigen::Vector3d origin_;
  const OcclusionScene& scene_;
  double min_rise_;
  double margin_rad_;
  double clear_margin_rad_;
  double reach_m_;
};

}  // namespace

SkyEdges measureSkyEdges(const std::vector<ImageSegment>& image,
                         const Eigen::Isometry3d& T_world_camera, const PinholeCamera& camera,
                         const OcclusionScene& scene, const SkyEdgeOptions& options) {
  const SkyClassifier classify(T_world_camera, camera, scene, options);
  SkyEdges sky;
  for (const ImageSegment& segment : image) {
    const Eigen::Vector2d start = segment.start.cast<double>();
    const Eigen::Vector2d end = segment.end.cast<double>();
    const double length = (end - start).norm();
    if (length < options.min_segment_length_px) {
      continue;
    }
    const int samples = std::max(1, static_cast<int>(length / options.sample_spacing_px));
    for (int i = 0; i < samples; ++i) {
      const Sky sample = classify.at(start + (end - start) * ((i + 0.5) / samples));
      sky.edge_px += sample == Sky::kNone ? 0.0 : length / samples;
      sky.clear_edge_px += sample == Sky::kClear ? length / samples : 0.0;
    }
  }
  return sky;
}

double clearSkyArea(const Eigen::Isometry3d& T_world_camera, const PinholeCamera& camera,
                    const OcclusionScene& scene, const SkyEdgeOptions& options) {
  const SkyClassifier classify(T_world_camera, camera, scene, options);
  const int columns =
      std::max(1, static_cast<int>(std::ceil(camera.width / options.area_spacing_px)));
  const int rows =
      std::max(1, static_cast<int>(std::ceil(camera.height / options.area_spacing_px)));
  const double cell_width = static_cast<double>(camera.width) / columns;
  const double cell_height = static_cast<double>(camera.height) / rows;
  int clear_cells = 0;
  for (int row = 0; row < rows; ++row) {
    for (int column = 0; column < columns; ++column) {
      clear_cells +=
          classify.at({(column + 0.5) * cell_width, (row + 0.5) * cell_height}) == Sky::kClear;
    }
  }
  return clear_cells * cell_width * cell_height;
}

std::optional<double> clearSkyEdgeDensity(const SkyEdges& sky, double clear_area_px2,
                                          const SkyEdgeOptions& options) {
  if (clear_area_px2 < options.min_clear_area_px2) {
    return std::nullopt;
  }
  return sky.clear_edge_px / clear_area_px2;
}

double weighedSkyEdgeLength(const SkyEdges& sky, double clutter_density,
                            const SkyEdgeOptions& options) {
  const double facade = options.facade_edge_density;
  const double evidence = std::log(facade / std::max(clutter_density, 1e-12)) /
                          std::log(facade / options.typical_clutter_density);
  return std::clamp(evidence, 0.0, 1.0) * sky.edge_px;
}

}  // namespace lineloc
