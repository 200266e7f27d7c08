#include "backbone/tracker/scene_scale.h"

#include <fmt/format.h>

#include <algorithm>
#include <stdexcept>
#include <vector>

namespace lineloc {
namespace {

// Rays per image side: enough that a model filling a tenth of the image
// still meets dozens of them.
constexpr int kRaysPerSide = 40;

}  // namespace

double sceneMetresPerUnit(const OcclusionScene& scene, const PinholeCamera& camera,
                          const Eigen::Isometry3d& T_world_camera, double street_depth_m) {
  if (!(street_depth_m > 0.0)) {
    throw std::invalid_argument(
        fmt::format("street depth {} m of the scene scale must be positive", street_depth_m));
  }
  std::vector<double> depths_m;
  for (int row = 0; row < kRaysPerSide; ++row) {
    for (int column = 0; column < kRaysPerSide; ++column) {
      const double u = (column + 0.5) * camera.width / kRaysPerSide;
      const double v = (row + 0.5) * camera.height / kRaysPerSide;
      const Eigen::Vector3d ray_camera =
          Eigen::Vector3d((u - camera.cx) / camera.fx, (v - camera.cy) / camera.fy, 1.0)
              .normalized();
      const std::optional<SurfaceHit> hit =
          scene.firstSurface(T_world_camera.translation(), T_world_camera.linear() * ray_camera);
      if (hit) {
        depths_m.push_back(hit->distance_m * ray_camera.z());
      }
    }
  }
  if (depths_m.empty()) {
    return 1.0;
  }
  const auto middle = depths_m.begin() + static_cast<std::ptrdiff_t>(depths_m.size() / 2);
  std::nth_element(depths_m.begin(), middle, depths_m.end());
  return *middle / street_depth_m;
}

}  // namespace lineloc
