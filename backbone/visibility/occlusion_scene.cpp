#include "backbone/visibility/occlusion_scene.h"

#include <limits>
#include <stdexcept>

#include "common/geometry/polygon_triangulation.h"

namespace lineloc {
namespace {

struct Mesh {
  std::vector<float> vertices;  // x y z per vertex
  std::vector<unsigned> indices;
};

Mesh triangulate(const std::vector<FaceRing>& faces) {
  Mesh mesh;
  for (const FaceRing& ring : faces) {
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
  }
  return mesh;
}

}  // namespace

OcclusionScene::OcclusionScene(const std::vector<FaceRing>& faces)
    : device_(rtcNewDevice("threads=1")) {
  if (device_ == nullptr) {
    throw std::runtime_error("cannot create an Embree device");
  }
  scene_ = rtcNewScene(device_);
  const Mesh mesh = triangulate(faces);
  triangle_count_ = mesh.indices.size() / 3;
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
  RTCRay ray{};
  ray.org_x = static_cast<float>(from.x());
  ray.org_y = static_cast<float>(from.y());
  ray.org_z = static_cast<float>(from.z());
  ray.dir_x = static_cast<float>(direction.x());
  ray.dir_y = static_cast<float>(direction.y());
  ray.dir_z = static_cast<float>(direction.z());
  ray.tnear = 0.0f;
  ray.tfar = static_cast<float>(length - end_clearance_m);
  ray.mask = std::numeric_limits<unsigned>::max();
  rtcOccluded1(scene_, &context, &ray);
  return ray.tfar < 0.0f;  // Embree sets tfar to -inf on a hit
}

}  // namespace lineloc
