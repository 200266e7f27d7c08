#include "backbone/visibility/occlusion_scene.h"

#include <limits>
#include <stdexcept>
#include <string>
#include <utility>

#include "common/geometry/polygon_triangulation.h"

namespace lineloc {
namespace {

struct Mesh {
  std::vector<float> vertices;  // x y z per vertex
  std::vector<unsigned> indices;
  std::vector<int64_t> triangle_building_ids;
};

Mesh triangulate(const std::vector<FaceRing>& faces, const std::vector<int64_t>& building_ids) {
  if (building_ids.size() != faces.size()) {
    throw std::invalid_argument("OcclusionScene: " + std::to_string(building_ids.size()) +
                                " building ids for " + std::to_string(faces.size()) + " faces");
  }
  Mesh mesh;
  for (size_t face = 0; face < faces.size(); ++face) {
    const FaceRing& ring = faces[face];
    const unsigned base = static_cast<unsigned>(mesh.vertices.size() / 3);
    const auto triangles = triangulatePolygon(ring);
    if (triangles.empty()) {
      continue;
    }
    for (const Eigen::Vector3d& p : ring) {
      mesh.vertices.insert(
          mesh.vertices.end(),
          {static_cast<float>(p.x()), static_cast<float>(p.y()), static_cast<float>(p.z())});
    }
    for (const auto& t : triangles) {
      mesh.indices.insert(mesh.indices.end(), {base + t[0], base + t[1], base + t[2]});
    }
    mesh.triangle_building_ids.insert(mesh.triangle_building_ids.end(), triangles.size(),
                                      building_ids[face]);
  }
  return mesh;
}

RTCRay rayAlong(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction, float far) {
  RTCRay ray{};
  ray.org_x = static_cast<float>(origin.x());
  ray.org_y = static_cast<float>(origin.y());
  ray.org_z = static_cast<float>(origin.z());
  ray.dir_x = static_cast<float>(direction.x());
  ray.dir_y = static_cast<float>(direction.y());
  ray.dir_z = static_cast<float>(direction.z());
  ray.tnear = 0.0f;
  ray.tfar = far;
  ray.mask = std::numeric_limits<unsigned>::max();
  return ray;
}

}  // namespace

OcclusionScene::OcclusionScene(const std::vector<FaceRing>& faces,
                               const std::vector<int64_t>& building_ids) {
  Mesh mesh = triangulate(faces, building_ids);
  device_ = rtcNewDevice("threads=1");
  if (device_ == nullptr) {
    throw std::runtime_error("cannot create an Embree device");
  }
  scene_ = rtcNewScene(device_);
  triangle_count_ = mesh.indices.size() / 3;
  triangle_building_ids_ = std::move(mesh.triangle_building_ids);
  if (triangle_count_ > 0) {
    RTCGeometry geometry = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_TRIANGLE);
    auto* vertices = static_cast<float*>(
        rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                3 * sizeof(float), mesh.vertices.size() / 3));
    std::copy(mesh.vertices.begin(), mesh.vertices.end(), vertices);
    auto* indices = static_cast<unsigned*>(
        rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                3 * sizeof(unsigned), triangle_count_));
    std::copy(mesh.indices.begin(), mesh.indices.end(), indices);
    rtcCommitGeometry(geometry);
    rtcAttachGeometry(scene_, geometry);
    rtcReleaseGeometry(geometry);
  }
  rtcCommitScene(scene_);
}

OcclusionScene::~OcclusionScene() {
  rtcReleaseScene(scene_);
  rtcReleaseDevice(device_);
}

bool OcclusionScene::blocked(const Eigen::Vector3d& from, const Eigen::Vector3d& to,
                             double end_clearance_m) const {
  const Eigen::Vector3d path = to - from;
  const double length = path.norm();
  if (length <= end_clearance_m) {
    return false;
  }
  const Eigen::Vector3d direction = path / length;
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRay ray = rayAlong(from, direction, static_cast<float>(length - end_clearance_m));
  rtcOccluded1(scene_, &context, &ray);
  return ray.tfar < 0.0f;  // Embree sets tfar to -inf on a hit
}

int OcclusionScene::countClearPaths(std::span<const Eigen::Vector3d> origins,
                                    const Eigen::Vector3d& to, double end_clearance_m) const {
  if (origins.size() > kMaxPacketOrigins) {
    throw std::invalid_argument("OcclusionScene: " + std::to_string(origins.size()) +
                                " origins in one packet, at most " +
                                std::to_string(kMaxPacketOrigins));
  }
  if (origins.empty()) {
    return 0;
  }
  alignas(32) int valid[kMaxPacketOrigins] = {};
  alignas(32) RTCRay8 rays{};
  int clear = 0;
  for (size_t lane = 0; lane < origins.size(); ++lane) {
    const Eigen::Vector3d path = to - origins[lane];
    const double length = path.norm();
    if (length <= end_clearance_m) {
      ++clear;
      continue;
    }
    const RTCRay ray =
        rayAlong(origins[lane], path / length, static_cast<float>(length - end_clearance_m));
    valid[lane] = -1;
    rays.org_x[lane] = ray.org_x;
    rays.org_y[lane] = ray.org_y;
    rays.org_z[lane] = ray.org_z;
    rays.dir_x[lane] = ray.dir_x;
    rays.dir_y[lane] = ray.dir_y;
    rays.dir_z[lane] = ray.dir_z;
    rays.tnear[lane] = ray.tnear;
    rays.tfar[lane] = ray.tfar;
    rays.mask[lane] = ray.mask;
  }
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
  rtcOccluded8(valid, scene_, &context, &rays);
  for (size_t lane = 0; lane < origins.size(); ++lane) {
    clear += valid[lane] != 0 && rays.tfar[lane] >= 0.0f ? 1 : 0;
  }
  return clear;
}

std::optional<SurfaceHit> OcclusionScene::firstSurface(const Eigen::Vector3d& origin,
                                                       const Eigen::Vector3d& direction) const {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRayHit ray_hit{};
  ray_hit.ray = rayAlong(origin, direction, std::numeric_limits<float>::infinity());
  ray_hit.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rtcIntersect1(scene_, &context, &ray_hit);
  if (ray_hit.hit.geomID == RTC_INVALID_GEOMETRY_ID) {
    return std::nullopt;
  }
  const Eigen::Vector3d normal(ray_hit.hit.Ng_x, ray_hit.hit.Ng_y, ray_hit.hit.Ng_z);
  return SurfaceHit{normal.normalized(), triangle_building_ids_[ray_hit.hit.primID],
                    ray_hit.ray.tfar};
}

}  // namespace lineloc
