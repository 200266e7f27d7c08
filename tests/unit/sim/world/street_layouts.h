// Synthetic street layouts of box buildings for the street network and route
// tests.
#pragma once

#include "sim/render/scene_mesh.h"

namespace lineloc {

// A box building over x in [x0, x1], y in [y0, y1], 10 m high.
inline void addBuilding(double x0, double y0, double x1, double y1, uint32_t id, SceneMesh& mesh) {
  mesh.addBox(Eigen::Isometry3d(Eigen::Translation3d(0.5 * (x0 + x1), 0.5 * (y0 + y1), 5.0)),
              Eigen::Vector3d(0.5 * (x1 - x0), 0.5 * (y1 - y0), 5.0),
              SurfaceTag{SurfaceKind::kWall, id, 0.0f, 10.0f});
}

// A 14 m main street along y = 0 over x in [0, 200], running into open land
// at both ends, and a 14 m cul-de-sac off it along x = 100, closed by a
// building at y = 67.
inline constexpr double kCulDeSacX_m = 100.0;
inline constexpr double kCulDeSacEndY_m = 67.0;

inline SceneMesh makeCulDeSacCity() {
  SceneMesh mesh;
  uint32_t id = 1;
  for (int k = 0; k < 10; ++k) {
    addBuilding(20.0 * k, -27.0, 20.0 * (k + 1), -7.0, id++, mesh);
  }
  addBuilding(0.0, 7.0, kCulDeSacX_m - 7.0, kCulDeSacEndY_m, id++, mesh);
  addBuilding(kCulDeSacX_m + 7.0, 7.0, 200.0, kCulDeSacEndY_m, id++, mesh);
  addBuilding(kCulDeSacX_m - 27.0, kCulDeSacEndY_m, kCulDeSacX_m + 27.0, kCulDeSacEndY_m + 20.0,
              id++, mesh);
  return mesh;
}

}  // namespace lineloc
