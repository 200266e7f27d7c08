// Building faces as an Embree 3 ray-casting scene, asked one question: is the
// straight path between two points blocked by a face? (Wald et al., "Embree:
// A Kernel Framework for Efficient CPU Ray Tracing", SIGGRAPH 2014.)
//
// Coordinates are world (site-local) metres, small enough for Embree's floats.
#pragma once

#include <embree3/rtcore.h>

#include <Eigen/Core>
#include <vector>

namespace lineloc {

// A planar face: its outer ring, without the repeated closing vertex.
using FaceRing = std::vector<Eigen::Vector3d>;

class OcclusionScene {
 public:
  // Triangulates every face (degenerate ones are skipped) and builds the BVH.
  explicit OcclusionScene(const std::vector<FaceRing>& faces);
  ~OcclusionScene();
  OcclusionScene(const OcclusionScene&) = delete;
  OcclusionScene& operator=(const OcclusionScene&) = delete;

  // True when a face crosses the open segment from `from` to `to`, ignoring
  // the last `end_clearance_m` before `to` (the point itself lies on faces).
  bool blocked(const Eigen::Vector3d& from, const Eigen::Vector3d& to,
               double end_clearance_m) const;

  size_t triangleCount() const { return triangle_count_; }

 private:
  RTCDevice device_;
  RTCScene scene_;
  size_t triangle_count_ = 0;
};

}  // namespace lineloc
