// The triangles the simulator renders: buildings and terrain from the city
// model plus the things in front of them that the model does not hold (cars,
// trees, poles, pedestrians). Every triangle carries what it is made of and
// which object it belongs to, so the shader can give each building its own
// façade.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>
#include <vector>

namespace lineloc {

enum class SurfaceKind : uint8_t {
  kWall,
  kRoof,
  kCarBody,
  kCarWindow,
  kTreeTrunk,
  kFoliage,
  kPole,
  kPerson,
  kCable,
  kRoadMarking,
  kKerb,
  // The model's terrain, shaded as the ground plane is.
  kGround
};

// Per-triangle attributes the shader reads.
struct SurfaceTag {
  SurfaceKind kind = SurfaceKind::kWall;
  uint32_t object_id = 0;
  // Heights of the object's base and top (m): façade storeys count from the
  // base, and only whole storeys below the top get windows.
  float base_z = 0.0f;
  float top_z = 0.0f;
};

class SceneMesh {
 public:
  // Appends a triangle (counter-clockwise seen from outside) and its tag.
  void addTriangle(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                   const SurfaceTag& tag);
  // Appends a planar convex quad a-b-c-d as two triangles.
  void addQuad(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
               const Eigen::Vector3d& d, const SurfaceTag& tag);
  // Appends the six faces of the box [-half_size, half_size] placed by T_world_box.
  void addBox(const Eigen::Isometry3d& T_world_box, const Eigen::Vector3d& half_size,
              const SurfaceTag& tag);
  // Appends another mesh's triangles.
  void append(const SceneMesh& other);

  const std::vector<Eigen::Vector3f>& vertices() const { return vertices_; }
  // Triangle i uses vertices 3i, 3i+1, 3i+2.
  size_t triangleCount() const { return tags_.size(); }
  const SurfaceTag& tag(size_t triangle) const { return tags_[triangle]; }
  // Unit normal of triangle i, (b - a) x (c - a) normalised.
  const Eigen::Vector3f& normal(size_t triangle) const { return normals_[triangle]; }

 private:
  std::vector<Eigen::Vector3f> vertices_;
  std::vector<Eigen::Vector3f> normals_;
  std::vector<SurfaceTag> tags_;
};

}  // namespace lineloc
