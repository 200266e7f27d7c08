#include <gtest/gtest.h>

#include "sim/render/ray_caster.h"

namespace lineloc {
namespace {

// One ray from `origin` along unit `direction` in slot 0 of a packet.
RayPacket singleRay(const Eigen::Vector3f& origin, const Eigen::Vector3f& direction) {
  RayPacket rays;
  rays.origin_x[0] = origin.x();
  rays.origin_y[0] = origin.y();
  rays.origin_z[0] = origin.z();
  rays.direction_x[0] = direction.x();
  rays.direction_y[0] = direction.y();
  rays.direction_z[0] = direction.z();
  rays.t_near[0] = 0.0f;
  rays.t_far[0] = 1e4f;
  rays.active[0] = true;
  return rays;
}

SceneMesh unitCubeAt(const Eigen::Vector3d& centre) {
  SceneMesh mesh;
  mesh.addBox(Eigen::Isometry3d(Eigen::Translation3d(centre)), Eigen::Vector3d(0.5, 0.5, 0.5),
              SurfaceTag{SurfaceKind::kWall, 3, 0.0f, 1.0f});
  return mesh;
}

TEST(RayCaster, BoxFacesHaveOutwardNormals) {
  const SceneMesh mesh = unitCubeAt(Eigen::Vector3d::Zero());
  ASSERT_EQ(mesh.triangleCount(), 12u);
  for (size_t i = 0; i < mesh.triangleCount(); ++i) {
    const Eigen::Vector3f centroid =
        (mesh.vertices()[3 * i] + mesh.vertices()[3 * i + 1] + mesh.vertices()[3 * i + 2]) / 3.0f;
    EXPECT_GT(mesh.normal(i).dot(centroid), 0.0f) << "triangle " << i;
  }
}

TEST(RayCaster, HitsBoxAtAnalyticDistance) {
  const SceneMesh mesh = unitCubeAt({10.0, 2.0, 1.0});
  const RayCaster caster(mesh);
  const Eigen::Vector3f origin(0.0f, 0.0f, 0.0f);
  const Eigen::Vector3f target(9.5f, 2.1f, 1.2f);  // on the face x = 9.5
  const Eigen::Vector3f direction = (target - origin).normalized();
  PacketHits hits;
  caster.intersect(singleRay(origin, direction), hits);
  ASSERT_NE(hits.triangle[0], kNoTriangle);
  // Float arithmetic on a 10 m ray: ~1e-6 relative.
  EXPECT_NEAR(hits.t[0], (target - origin).norm(), 1e-4f);
  EXPECT_NEAR(mesh.normal(hits.triangle[0]).x(), -1.0f, 1e-6f);
  for (int i = 1; i < kRayPacketSize; ++i) {
    EXPECT_EQ(hits.triangle[i], kNoTriangle) << "inactive ray " << i;
  }
}

TEST(RayCaster, MissesWhenPointingAway) {
  const RayCaster caster(unitCubeAt({10.0, 0.0, 0.0}));
  PacketHits hits;
  caster.intersect(singleRay(Eigen::Vector3f::Zero(), -Eigen::Vector3f::UnitX()), hits);
  EXPECT_EQ(hits.triangle[0], kNoTriangle);
}

TEST(RayCaster, OcclusionRespectsRayLength) {
  const RayCaster caster(unitCubeAt({10.0, 0.0, 0.0}));
  RayPacket rays = singleRay(Eigen::Vector3f::Zero(), Eigen::Vector3f::UnitX());
  std::array<bool, kRayPacketSize> occluded{};
  caster.occluded(rays, occluded);
  EXPECT_TRUE(occluded[0]);
  rays.t_far[0] = 9.0f;  // stops before the box
  caster.occluded(rays, occluded);
  EXPECT_FALSE(occluded[0]);
}

TEST(RayCaster, EmptySceneNeverHits) {
  const RayCaster caster{SceneMesh{}};
  PacketHits hits;
  caster.intersect(singleRay(Eigen::Vector3f::Zero(), Eigen::Vector3f::UnitX()), hits);
  EXPECT_EQ(hits.triangle[0], kNoTriangle);
}

}  // namespace
}  // namespace lineloc
