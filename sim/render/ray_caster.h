// Ray casting against a SceneMesh with Embree 3: one BVH built once, then
// packets of 16 coherent rays (a 4x4 pixel tile or the shadow rays of one)
// for the closest hit or for any occluder.
#pragma once

#include <array>
#include <cstdint>
#include <limits>
#include <memory>

#include "sim/render/scene_mesh.h"

namespace lineloc {

inline constexpr int kRayPacketSize = 16;
inline constexpr uint32_t kNoTriangle = std::numeric_limits<uint32_t>::max();

// Structure-of-arrays rays; `active[i]` false skips ray i.
struct RayPacket {
  alignas(64) std::array<float, kRayPacketSize> origin_x{};
  alignas(64) std::array<float, kRayPacketSize> origin_y{};
  alignas(64) std::array<float, kRayPacketSize> origin_z{};
  alignas(64) std::array<float, kRayPacketSize> direction_x{};
  alignas(64) std::array<float, kRayPacketSize> direction_y{};
  alignas(64) std::array<float, kRayPacketSize> direction_z{};
  alignas(64) std::array<float, kRayPacketSize> t_near{};
  alignas(64) std::array<float, kRayPacketSize> t_far{};
  std::array<bool, kRayPacketSize> active{};
};

// Closest hits: distance along the (unit) direction and the triangle index in
// the SceneMesh, kNoTriangle for a miss or an inactive ray.
struct PacketHits {
  std::array<float, kRayPacketSize> t{};
  std::array<uint32_t, kRayPacketSize> triangle{};
};

class RayCaster {
 public:
  // Builds the BVH; throws std::runtime_error with Embree's message on failure.
  explicit RayCaster(const SceneMesh& mesh);
  ~RayCaster();
  RayCaster(const RayCaster&) = delete;
  RayCaster& operator=(const RayCaster&) = delete;

  void intersect(const RayPacket& rays, PacketHits& hits) const;
  // occluded[i]: something lies on ray i between t_near and t_far.
  void occluded(const RayPacket& rays, std::array<bool, kRayPacketSize>& occluded) const;

 private:
  struct Embree;
  std::unique_ptr<Embree> embree_;
};

}  // namespace lineloc
