// Building faces as an Embree 3 ray-casting scene, asked two questions: is the
// straight path between two points blocked by a face, and which surface does a
// ray meet first? (Wald et al., "Embree: A Kernel Framework for Efficient CPU
// Ray Tracing", SIGGRAPH 2014.)
//
// Coordinates are world (site-local) metres, small enough for Embree's floats.
#pragma once

#include <embree3/rtcore.h>

#include <Eigen/Core>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

namespace lineloc {

// A planar face: its outer ring, without the repeated closing vertex.
using FaceRing = std::vector<Eigen::Vector3d>;

// What a ray meets first: the plane and the building of a face, and how far
// along the (unit) ray.
struct SurfaceHit {
  Eigen::Vector3d unit_normal = Eigen::Vector3d::Zero();  // sign as the ring winds
  int64_t building_id = 0;
  double distance_m = 0.0;
};

class OcclusionScene {
 public:
  // Triangulates every face (degenerate ones are skipped) and builds the BVH.
  // faces[i] belongs to building building_ids[i]: visibility finds an edge
  // between flush façades only where their buildings differ.
  OcclusionScene(const std::vector<FaceRing>& faces, const std::vector<int64_t>& building_ids);
  ~OcclusionScene();
  OcclusionScene(const OcclusionScene&) = delete;
  OcclusionScene& operator=(const OcclusionScene&) = delete;

  // True when a face crosses the open segment from `from` to `to`, ignoring
  // the last `end_clearance_m` before `to` (the point itself lies on faces).
  bool blocked(const Eigen::Vector3d& from, const Eigen::Vector3d& to,
               double end_clearance_m) const;

  // How many of the paths from `origins` to `to` no face crosses: blocked()
  // for up to kMaxPacketOrigins origins at once, traced as one ray packet.
  // Rays converging on one point from nearby origins share most of their way
  // through the BVH, so the packet costs little more than one ray.
  static constexpr size_t kMaxPacketOrigins = 8;
  int countClearPaths(std::span<const Eigen::Vector3d> origins, const Eigen::Vector3d& to,
                      double end_clearance_m) const;

  // The first face on the ray from `origin` along `direction`, or nothing (the
  // ray leaves the model: sky or ground).
  std::optional<SurfaceHit> firstSurface(const Eigen::Vector3d& origin,
                                         const Eigen::Vector3d& direction) const;

  size_t triangleCount() const { return triangle_count_; }

 private:
  RTCDevice device_;
  RTCScene scene_;
  size_t triangle_count_ = 0;
  std::vector<int64_t> triangle_building_ids_;
};

}  // namespace lineloc
