#include <gtest/gtest.h>

#include <set>

#include "sim/render/facade_layout.h"
#include "sim/render/surface_shader.h"

namespace lineloc {
namespace {

// The albedos the shader gives a wall facing -y of a 20 m building, sampled
// over 16 m by 20 m, seen closely enough for the brick.
std::set<float> wallAlbedos(const ShadingOptions& options, uint32_t object_id) {
  const SurfaceShader shader(options);
  const SurfaceTag tag{SurfaceKind::kWall, object_id, 0.0f, 20.0f};
  std::set<float> albedos;
  for (float x = -8.0f; x < 8.0f; x += 0.13f) {
    for (float z = 0.0f; z < 20.0f; z += 0.11f) {
      albedos.insert(shader.meshAlbedo(tag, {x, 0.0f, z}, {0.0f, -1.0f, 0.0f}, 0.002f));
    }
  }
  return albedos;
}

TEST(SurfaceShader, AWallWithoutFacadeDetailIsItsBuildingsOneAlbedo) {
  ShadingOptions bare;
  bare.facade_detail = false;
  for (uint32_t id = 1; id <= 10; ++id) {
    EXPECT_GT(wallAlbedos(ShadingOptions{}, id).size(), 2u) << id;
    EXPECT_EQ(wallAlbedos(bare, id), std::set<float>{FacadeLayout(id, 0.0f, 20.0f).wallAlbedo()})
        << id;
  }
}

}  // namespace
}  // namespace lineloc
