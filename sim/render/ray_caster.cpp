#include "sim/render/ray_caster.h"

#include <embree3/rtcore.h>
#include <fmt/format.h>

#include <cstring>
#include <stdexcept>

namespace lineloc {

struct RayCaster::Embree {
  RTCDevice device = nullptr;
  RTCScene scene = nullptr;
  ~Embree() {
    if (scene != nullptr) {
      rtcReleaseScene(scene);
    }
    if (device != nullptr) {
      rtcReleaseDevice(device);
    }
  }
};

namespace {

[[noreturn]] void throwEmbreeError(RTCDevice device, const char* what) {
  throw std::runtime_error(fmt::format("RayCaster: {} failed (Embree error {})", what,
                                       static_cast<int>(rtcGetDeviceError(device))));
}

std::array<int, kRayPacketSize> validMask(const RayPacket& rays) {
  std::array<int, kRayPacketSize> valid{};
  for (int i = 0; i < kRayPacketSize; ++i) {
    valid[i] = rays.active[i] ? -1 : 0;
  }
  return valid;
}

void copyRays(const RayPacket& rays, RTCRay16& ray) {
  std::memcpy(ray.org_x, rays.origin_x.data(), sizeof(ray.org_x));
  std::memcpy(ray.org_y, rays.origin_y.data(), sizeof(ray.org_y));
  std::memcpy(ray.org_z, rays.origin_z.data(), sizeof(ray.org_z));
  std::memcpy(ray.dir_x, rays.direction_x.data(), sizeof(ray.dir_x));
  std::memcpy(ray.dir_y, rays.direction_y.data(), sizeof(ray.dir_y));
  std::memcpy(ray.dir_z, rays.direction_z.data(), sizeof(ray.dir_z));
  std::memcpy(ray.tnear, rays.t_near.data(), sizeof(ray.tnear));
  std::memcpy(ray.tfar, rays.t_far.data(), sizeof(ray.tfar));
  for (int i = 0; i < kRayPacketSize; ++i) {
    ray.time[i] = 0.0f;
    ray.mask[i] = ~0u;
    ray.id[i] = static_cast<unsigned>(i);
    ray.flags[i] = 0;
  }
}

RTCIntersectContext coherentContext() {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
  return context;
}

}  // namespace

RayCaster::RayCaster(const SceneMesh& mesh) : embree_(std::make_unique<Embree>()) {
  // One build thread: the simulator's budget is one core.
  embree_->device = rtcNewDevice("threads=1");
  if (embree_->device == nullptr) {
    throw std::runtime_error("RayCaster: rtcNewDevice failed");
  }
  RTCDevice device = embree_->device;
  embree_->scene = rtcNewScene(device);
  rtcSetSceneBuildQuality(embree_->scene, RTC_BUILD_QUALITY_HIGH);
  const size_t triangle_count = mesh.triangleCount();
  if (triangle_count > 0) {
    RTCGeometry geometry = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
    // Embree reads 16 bytes past the last float3: allocate one extra vertex.
    auto* vertices = static_cast<float*>(
        rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                3 * sizeof(float), mesh.vertices().size() + 1));
    auto* indices = static_cast<unsigned*>(
        rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                3 * sizeof(unsigned), triangle_count));
    if (vertices == nullptr || indices == nullptr) {
      rtcReleaseGeometry(geometry);
      throwEmbreeError(device, "allocating the geometry buffers");
    }
    for (size_t i = 0; i < mesh.vertices().size(); ++i) {
      std::memcpy(vertices + 3 * i, mesh.vertices()[i].data(), 3 * sizeof(float));
    }
    for (size_t i = 0; i < 3 * triangle_count; ++i) {
      indices[i] = static_cast<unsigned>(i);
    }
    rtcCommitGeometry(geometry);
    rtcAttachGeometry(embree_->scene, geometry);
    rtcReleaseGeometry(geometry);
  }
  rtcCommitScene(embree_->scene);
  if (rtcGetDeviceError(device) != RTC_ERROR_NONE) {
    throwEmbreeError(device, "building the scene");
  }
}

RayCaster::~RayCaster() = default;

void RayCaster::intersect(const RayPacket& rays, PacketHits& hits) const {
  alignas(64) RTCRayHit16 ray_hit;
  copyRays(rays, ray_hit.ray);
  for (int i = 0; i < kRayPacketSize; ++i) {
    ray_hit.hit.geomID[i] = RTC_INVALID_GEOMETRY_ID;
    ray_hit.hit.instID[0][i] = RTC_INVALID_GEOMETRY_ID;
  }
  RTCIntersectContext context = coherentContext();
  alignas(64) const std::array<int, kRayPacketSize> valid = validMask(rays);
  rtcIntersect16(valid.data(), embree_->scene, &context, &ray_hit);
  for (int i = 0; i < kRayPacketSize; ++i) {
    const bool hit = rays.active[i] && ray_hit.hit.geomID[i] != RTC_INVALID_GEOMETRY_ID;
    hits.t[i] = hit ? ray_hit.ray.tfar[i] : std::numeric_limits<float>::infinity();
    hits.triangle[i] = hit ? ray_hit.hit.primID[i] : kNoTriangle;
  }
}

void RayCaster::occluded(const RayPacket& rays, std::array<bool, kRayPacketSize>& occluded) const {
  alignas(64) RTCRay16 ray;
  copyRays(rays, ray);
  RTCIntersectContext context = coherentContext();
  alignas(64) const std::array<int, kRayPacketSize> valid = validMask(rays);
  rtcOccluded16(valid.data(), embree_->scene, &context, &ray);
  // Embree marks an occluded ray by setting tfar to -inf.
  for (int i = 0; i < kRayPacketSize; ++i) {
    occluded[i] = rays.active[i] && ray.tfar[i] < 0.0f;
  }
}

}  // namespace lineloc
