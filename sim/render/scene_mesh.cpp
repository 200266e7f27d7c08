#include "sim/render/scene_mesh.h"

#include <array>

namespace lineloc {

void SceneMesh::addTriangle(const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                            const Eigen::Vector3d& c, const SurfaceTag& tag) {
  const Eigen::Vector3d normal = (b - a).cross(c - a);
  const double norm = normal.norm();
  if (!(norm > 0.0)) {
    return;  // degenerate: no area, never hit
  }
  vertices_.push_back(a.cast<float>());
  vertices_.push_back(b.cast<float>());
  vertices_.push_back(c.cast<float>());
  normals_.push_back((normal / norm).cast<float>());
  tags_.push_back(tag);
}

void SceneMesh::addQuad(const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                        const Eigen::Vector3d& c, const Eigen::Vector3d& d, const SurfaceTag& tag) {
  addTriangle(a, b, c, tag);
  addTriangle(a, c, d, tag);
}

void SceneMesh::addBox(const Eigen::Isometry3d& T_world_box, const Eigen::Vector3d& half_size,
                       const SurfaceTag& tag) {
  std::array<Eigen::Vector3d, 8> corners;
  for (int i = 0; i < 8; ++i) {
    const Eigen::Vector3d sign((i & 1) ? 1.0 : -1.0, (i & 2) ? 1.0 : -1.0, (i & 4) ? 1.0 : -1.0);
    corners[i] = T_world_box * sign.cwiseProduct(half_size);
  }
  // Corner index bits: x = 1, y = 2, z = 4; each face counter-clockwise from outside.
  constexpr int kFaces[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                                {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& face : kFaces) {
    addQuad(corners[face[0]], corners[face[1]], corners[face[2]], corners[face[3]], tag);
  }
}

void SceneMesh::append(const SceneMesh& other) {
  vertices_.insert(vertices_.end(), other.vertices_.begin(), other.vertices_.end());
  normals_.insert(normals_.end(), other.normals_.begin(), other.normals_.end());
  tags_.insert(tags_.end(), other.tags_.begin(), other.tags_.end());
}

}  // namespace lineloc
