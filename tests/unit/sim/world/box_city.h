// A test city: `blocks` x `blocks` square blocks of 4 box buildings each on a
// street grid, streets `street_m` wide, origin at the first block's corner.
#pragma once

#include "sim/render/scene_mesh.h"

namespace lineloc {

inline constexpr double kBoxCityBlock_m = 40.0;

inline SceneMesh makeBoxCity(int blocks, double street_m) {
  SceneMesh mesh;
  uint32_t id = 1;
  const double pitch = kBoxCityBlock_m + street_m;
  for (int bx = 0; bx < blocks; ++bx) {
    for (int by = 0; by < blocks; ++by) {
      for (int k = 0; k < 4; ++k) {
        const double height = 8.0 + 3.0 * ((id * 7) % 5);
        const Eigen::Vector3d centre(bx * pitch + (k % 2 + 0.5) * kBoxCityBlock_m / 2,
                                     by * pitch + (k / 2 + 0.5) * kBoxCityBlock_m / 2, height / 2);
        mesh.addBox(
            Eigen::Isometry3d(Eigen::Translation3d(centre)),
            Eigen::Vector3d(kBoxCityBlock_m / 4 - 0.5, kBoxCityBlock_m / 4 - 0.5, height / 2),
            SurfaceTag{SurfaceKind::kWall, id, 0.0f, static_cast<float>(height)});
        ++id;
      }
    }
  }
  return mesh;
}

}  // namespace lineloc
