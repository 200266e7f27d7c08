#include "sim/render/city_renderer.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace lineloc {
namespace {

constexpr int kTileSize = 4;
static_assert(kTileSize * kTileSize == kRayPacketSize);
// Shadow rays start this far off the surface so they do not hit it again (m).
constexpr float kShadowRayOffset_m = 2e-3f;
// Grazing views stretch the footprint by 1 / cos; capped at this cosine.
constexpr float kMinFootprintCosine = 0.2f;

const RenderOptions& validated(const RenderOptions& options) {
  if (!(options.exposure > 0.0f) || !(options.noise_sigma >= 0.0f) ||
      options.motion_blur_samples < 1) {
    throw std::invalid_argument(
        fmt::format("CityRenderer: exposure must be > 0 ({}), noise_sigma >= 0 ({}), "
                    "motion_blur_samples >= 1 ({})",
                    options.exposure, options.noise_sigma, options.motion_blur_samples));
  }
  return options;
}

// Pose at fraction s of the way from a to b (linear position, slerped rotation).
Eigen::Isometry3d interpolate(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b, double s) {
  const Eigen::Quaterniond qa(a.linear());
  const Eigen::Quaterniond qb(b.linear());
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() = qa.slerp(s, qb).toRotationMatrix();
  pose.translation() = (1.0 - s) * a.translation() + s * b.translation();
  return pose;
}

}  // namespace

CityRenderer::CityRenderer(const SceneMesh& mesh, const CameraCalibration& calibration,
                           const RenderOptions& options)
    : mesh_(mesh),
      options_(validated(options)),
      rays_(calibration),
      caster_(mesh_),
      shader_(options.shading),
      pixel_angle_rad_(static_cast<float>(1.0 / calibration.camera.fx)) {}

void CityRenderer::castTile(const Eigen::Matrix3f& R_world_camera, const Eigen::Vector3f& origin,
                            int u0, int v0, RayPacket& rays, PacketHits& hits) const {
  const float ground_z = options_.ground_z_m;
  for (int i = 0; i < kRayPacketSize; ++i) {
    const int u = u0 + i % kTileSize;
    const int v = v0 + i / kTileSize;
    const bool inside = u < rays_.width() && v < rays_.height();
    const Eigen::Vector3f d =
        inside ? Eigen::Vector3f(R_world_camera * rays_.direction(u, v)) : Eigen::Vector3f::Zero();
    rays.origin_x[i] = origin.x();
    rays.origin_y[i] = origin.y();
    rays.origin_z[i] = origin.z();
    rays.direction_x[i] = d.x();
    rays.direction_y[i] = d.y();
    rays.direction_z[i] = d.z();
    rays.t_near[i] = 0.0f;
    // The ground plane z = ground_z ends every downward ray: t = (ground_z - o_z) / d_z.
    rays.t_far[i] = d.z() < 0.0f && origin.z() > ground_z ? (ground_z - origin.z()) / d.z()
                                                          : std::numeric_limits<float>::infinity();
    rays.active[i] = inside && d.squaredNorm() > 0.0f;
  }
  caster_.intersect(rays, hits);
  for (int i = 0; i < kRayPacketSize; ++i) {
    if (rays.active[i] && hits.triangle[i] == kNoTriangle && std::isfinite(rays.t_far[i])) {
      hits.triangle[i] = kGroundTriangle;
      hits.t[i] = rays.t_far[i];
    }
  }
}

PixelHits CityRenderer::castPrimaryRays(const Eigen::Isometry3d& T_world_camera) const {
  PixelHits pixels;
  pixels.width = rays_.width();
  pixels.height = rays_.height();
  pixels.triangle.assign(static_cast<size_t>(pixels.width) * pixels.height, kNoTriangle);
  pixels.distance_m.assign(pixels.triangle.size(), std::numeric_limits<float>::infinity());
  const Eigen::Matrix3f R = T_world_camera.linear().cast<float>();
  const Eigen::Vector3f origin = T_world_camera.translation().cast<float>();
  RayPacket rays;
  PacketHits hits;
  for (int v0 = 0; v0 < pixels.height; v0 += kTileSize) {
    for (int u0 = 0; u0 < pixels.width; u0 += kTileSize) {
      castTile(R, origin, u0, v0, rays, hits);
      for (int i = 0; i < kRayPacketSize; ++i) {
        if (rays.active[i]) {
          const size_t index = (v0 + i / kTileSize) * pixels.width + u0 + i % kTileSize;
          pixels.triangle[index] = hits.triangle[i];
          pixels.distance_m[index] = hits.t[i];
        }
      }
    }
  }
  return pixels;
}

void CityRenderer::shadeTile(const RayPacket& rays, const PacketHits& hits, int u0, int v0,
                             cv::Mat& radiance) const {
  RayPacket shadow_rays;
  std::array<Eigen::Vector3f, kRayPacketSize> normals;
  std::array<float, kRayPacketSize> albedo{};
  for (int i = 0; i < kRayPacketSize; ++i) {
    shadow_rays.active[i] = false;
    if (!rays.active[i] || hits.triangle[i] == kNoTriangle) {
      continue;
    }
    const Eigen::Vector3f d(rays.direction_x[i], rays.direction_y[i], rays.direction_z[i]);
    const Eigen::Vector3f p =
        Eigen::Vector3f(rays.origin_x[i], rays.origin_y[i], rays.origin_z[i]) + hits.t[i] * d;
    const bool ground = hits.triangle[i] == kGroundTriangle;
    Eigen::Vector3f n = ground ? Eigen::Vector3f::UnitZ() : mesh_.normal(hits.triangle[i]);
    if (n.dot(d) > 0.0f) {
      n = -n;  // shade the side the camera sees
    }
    const float footprint_m =
        hits.t[i] * pixel_angle_rad_ / std::max(-n.dot(d), kMinFootprintCosine);
    albedo[i] = ground ? shader_.groundAlbedo(p, footprint_m)
                       : shader_.meshAlbedo(mesh_.tag(hits.triangle[i]), p, n, footprint_m);
    normals[i] = n;
    if (options_.shadows && shader_.facesSun(n)) {
      const Eigen::Vector3f start = p + kShadowRayOffset_m * n;
      shadow_rays.origin_x[i] = start.x();
      shadow_rays.origin_y[i] = start.y();
      shadow_rays.origin_z[i] = start.z();
      shadow_rays.direction_x[i] = shader_.sunDirection().x();
      shadow_rays.direction_y[i] = shader_.sunDirection().y();
      shadow_rays.direction_z[i] = shader_.sunDirection().z();
      shadow_rays.t_near[i] = 0.0f;
      shadow_rays.t_far[i] = std::numeric_limits<float>::infinity();
      shadow_rays.active[i] = true;
    }
  }
  std::array<bool, kRayPacketSize> in_shadow{};
  if (std::any_of(shadow_rays.active.begin(), shadow_rays.active.end(), [](bool a) { return a; })) {
    caster_.occluded(shadow_rays, in_shadow);
  }
  for (int i = 0; i < kRayPacketSize; ++i) {
    if (!rays.active[i]) {
      continue;
    }
    const Eigen::Vector3f d(rays.direction_x[i], rays.direction_y[i], rays.direction_z[i]);
    radiance.at<float>(v0 + i / kTileSize, u0 + i % kTileSize) =
        hits.triangle[i] == kNoTriangle ? shader_.skyRadiance(d)
                                        : albedo[i] * shader_.irradiance(normals[i], in_shadow[i]);
  }
}

cv::Mat CityRenderer::renderRadiance(const Eigen::Isometry3d& T_world_camera) const {
  cv::Mat radiance(rays_.height(), rays_.width(), CV_32FC1, cv::Scalar(0.0f));
  const Eigen::Matrix3f R = T_world_camera.linear().cast<float>();
  const Eigen::Vector3f origin = T_world_camera.translation().cast<float>();
  RayPacket rays;
  PacketHits hits;
  for (int v0 = 0; v0 < rays_.height(); v0 += kTileSize) {
    for (int u0 = 0; u0 < rays_.width(); u0 += kTileSize) {
      castTile(R, origin, u0, v0, rays, hits);
      shadeTile(rays, hits, u0, v0, radiance);
    }
  }
  return radiance;
}

cv::Mat CityRenderer::renderImage(const Eigen::Isometry3d& T_world_camera_open,
                                  const Eigen::Isometry3d& T_world_camera_close,
                                  uint64_t noise_seed) const {
  const int samples = options_.motion_blur_samples;
  cv::Mat radiance;
  if (samples == 1) {
    radiance = renderRadiance(interpolate(T_world_camera_open, T_world_camera_close, 0.5));
  } else {
    radiance = cv::Mat::zeros(rays_.height(), rays_.width(), CV_32FC1);
    for (int k = 0; k < samples; ++k) {
      const double s = (k + 0.5) / samples;
      radiance += renderRadiance(interpolate(T_world_camera_open, T_world_camera_close, s));
    }
    radiance /= samples;
  }
  cv::Mat grey = radiance * (255.0f * options_.exposure);
  if (options_.noise_sigma > 0.0f) {
    cv::Mat noise(grey.size(), CV_32FC1);
    cv::RNG rng(noise_seed);
    rng.fill(noise, cv::RNG::NORMAL, 0.0, options_.noise_sigma);
    grey += noise;
  }
  cv::Mat image;
  grey.convertTo(image, CV_8UC1);
  return image;
}

}  // namespace lineloc
