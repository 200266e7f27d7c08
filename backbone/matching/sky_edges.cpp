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

}  // namespace

double skyEdgeLength(const std::vector<ImageSegment>& image,
                     const Eigen::Isometry3d& T_world_camera, const PinholeCamera& camera,
                     const OcclusionScene& scene, const SkyEdgeOptions& options) {
  const Eigen::Matrix3d ray_from_pixel = T_world_camera.linear() * camera.K().inverse();
  const Eigen::Vector3d& origin = T_world_camera.translation();
  const double min_rise = std::sin(options.min_elevation_rad);
  const double margin_rad = options.margin_px / camera.fx;
  const auto meetsFace = [&](const Eigen::Vector3d& direction) {
    return scene.blocked(origin, origin + options.reach_m * direction, 0.0);
  };
  double sky_px = 0.0;
  for (const ImageSegment& segment : image) {
    const Eigen::Vector2d start = segment.start.cast<double>();
    const Eigen::Vector2d end = segment.end.cast<double>();
    const double length = (end - start).norm();
    if (length < options.min_segment_length_px) {
      continue;
    }
    const int samples = std::max(1, static_cast<int>(length / options.sample_spacing_px));
    const double sample_px = length / samples;
    for (int i = 0; i < samples; ++i) {
      const Eigen::Vector2d pixel = start + (end - start) * ((i + 0.5) / samples);
      const Eigen::Vector3d direction = (ray_from_pixel * pixel.homogeneous()).normalized();
      if (direction.z() < min_rise || meetsFace(direction) ||
          meetsFace(lowered(direction, margin_rad))) {
        continue;
      }
      sky_px += sample_px;
    }
  }
  return sky_px;
}

}  // namespace lineloc
