#include <gtest/gtest.h>

#include <cmath>

#include "sim/render/facade_layout.h"

namespace lineloc {
namespace {

// A building 20 m high: every storey has windows.
constexpr float kBase_m = 2.0f;
constexpr float kTop_m = 22.0f;

TEST(FacadeLayout, TheSameIdPaintsTheSameFacade) {
  const FacadeLayout a(7, kBase_m, kTop_m), b(7, kBase_m, kTop_m);
  for (float u = -10.0f; u < 10.0f; u += 0.37f) {
    for (float v = 0.0f; v < 20.0f; v += 0.41f) {
      EXPECT_EQ(a.at(u, v).albedo, b.at(u, v).albedo);
    }
  }
}

TEST(FacadeLayout, EveryBorderSeparatesTwoPaintsSomewhere) {
  // A border is where an element starts: across most of its length what is
  // painted on one side differs from the other.
  for (uint32_t id = 1; id <= 20; ++id) {
    const FacadeLayout layout(id, kBase_m, kTop_m);
    const std::vector<WallBorder> borders = layout.borders(-8.0, 8.0, 20.0);
    ASSERT_FALSE(borders.empty());
    int with_step = 0;
    for (const WallBorder& border : borders) {
      const Eigen::Vector2d along = border.to_uv - border.from_uv;
      const Eigen::Vector2d across = Eigen::Vector2d(-along.y(), along.x()).normalized() * 0.005;
      const auto paint = [&](const Eigen::Vector2d& uv) {
        return layout.at(static_cast<float>(uv.x()), static_cast<float>(uv.y())).albedo;
      };
      // At its quarters: a window's mullion meets the inner frame's middle.
      bool steps = false;
      for (const double t : {0.25, 0.75}) {
        const Eigen::Vector2d point = border.from_uv + t * along;
        steps = steps || std::abs(paint(point + across) - paint(point - across)) > 0.05f;
      }
      with_step += steps;
    }
    // Two signs side by side share a border with no step, and a door cuts a sign.
    EXPECT_GT(with_step, 0.9 * static_cast<double>(borders.size())) << "building " << id;
  }
}

TEST(FacadeLayout, AStoreyAboveTheTopHasNoWindows) {
  // 2.9-3.4 m storeys: a 4 m building has only its ground floor.
  for (uint32_t id = 1; id <= 20; ++id) {
    const FacadeLayout low(id, 0.0f, 4.0f);
    for (float u = -6.0f; u < 6.0f; u += 0.05f) {
      EXPECT_TRUE(low.at(u, 4.5f).bare_wall) << "building " << id << " u " << u;
    }
    for (const WallBorder& border : low.borders(-6.0, 6.0, 8.0)) {
      EXPECT_LE(std::max(border.from_uv.y(), border.to_uv.y()), 3.5) << "building " << id;
    }
  }
}

TEST(FacadeLayout, WallCoordinateRunsAlongTheWall) {
  const Eigen::Vector3f normal = Eigen::Vector3f(3.0f, 4.0f, 0.0f).normalized();
  const Eigen::Vector3f along(-4.0f / 5.0f, 3.0f / 5.0f, 0.0f);
  const Eigen::Vector3f point(10.0f, -3.0f, 5.0f);
  const float u = FacadeLayout::wallU(point, normal);
  EXPECT_NEAR(FacadeLayout::wallU(point + 2.5f * along, normal) - u, 2.5f, 1e-4f);
  EXPECT_NEAR(FacadeLayout::wallU(point + 2.0f * normal + Eigen::Vector3f(0, 0, 3), normal), u,
              1e-4f);
}

}  // namespace
}  // namespace lineloc
