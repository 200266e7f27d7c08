#include "sim/render/city_renderer.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <stdexcept>

namespace lineloc {
namespace {

constexpr int kTileSize = 4;
static_assert(kTileSize * kTileSize == kRayPacketSize);
// Shadow rays start this far off the surface so they do not hit it again (m).
constexpr float kShadowRayOffset_m = 2e-3f;
// Grazing views stretch the footprint by 1 / cos; capped at this cosine.
constexpr float kMinFootprintCosine = 0.2f;
// Faces of one object meet at a crease when their normals part by more than
// about 2.5 degrees.
constexpr float kCreaseCosine = 0.999f;
// Neighbouring pixels on one object and face orientation are a step, not one
// surface, when their distances differ by more than this fraction (a wall
// seen at 85 degrees from its normal changes by 2 % per pixel at f = 536 px).
constexpr float kDepthStepFraction = 0.1f;

const RenderOptions& validated(const RenderOptions& options) {
  if (!(options.exposure > 0.0f) || !(options.noise_sigma >= 0.0f) ||
      options.motion_blur_samples < 1 || options.edge_pixel_samples < 1 ||
      options.edge_pixel_samples > kRayPacketSize) {
    throw std::invalid_argument(
        fmt::format("CityRenderer: exposure must be > 0 ({}), noise_sigma >= 0 ({}), "
                    "motion_blur_samples >= 1 ({}), edge_pixel_samples 1 to {} ({})",
                    options.exposure, options.noise_sigma, options.motion_blur_samples,
                    kRayPacketSize, options.edge_pixel_samples));
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

// Every pixel seeing the sky, at infinity.
PixelHits noHits(int width, int height) {
  PixelHits pixels;
  pixels.width = width;
  pixels.height = height;
  pixels.triangle.assign(static_cast<size_t>(width) * height, kNoTriangle);
  pixels.distance_m.assign(pixels.triangle.size(), std::numeric_limits<float>::infinity());
  return pixels;
}

// The n points of the rank-1 lattice (k / n, frac(k g / n)), shifted by half a
// cell and centred on the pixel, whose generator g (coprime to n) keeps its
// nearest two points farthest apart on the torus; the lattice is a group, so
// that distance is the nearest point's to point 0.
std::vector<Eigen::Vector2f> rankOneLatticeOffsets(int n) {
  const auto torusDistance = [n](int k, int g) {
    const double x = static_cast<double>(k) / n;
    const double y = static_cast<double>(k * g % n) / n;
    return std::hypot(std::min(x, 1.0 - x), std::min(y, 1.0 - y));
  };
  int best_generator = 1;
  double best_distance = 0.0;
  for (int g = 1; g < n; ++g) {
    if (std::gcd(g, n) != 1) {
      continue;
    }
    double nearest = std::numeric_limits<double>::infinity();
    for (int k = 1; k < n; ++k) {
      nearest = std::min(nearest, torusDistance(k, g));
    }
    if (nearest > best_distance) {
      best_distance = nearest;
      best_generator = g;
    }
  }
  std::vector<Eigen::Vector2f> offsets_px;
  for (int k = 0; k < n; ++k) {
    offsets_px.emplace_back((k + 0.5f) / n - 0.5f, (k * best_generator % n + 0.5f) / n - 0.5f);
  }
  return offsets_px;
}

}  // namespace

CityRenderer::CityRenderer(const SceneMesh& mesh, const CameraCalibration& calibration,
                           const RenderOptions& options)
    : mesh_(mesh),
      options_(validated(options)),
      rays_(calibration),
      caster_(mesh_),
      shader_(options.shading),
      pixel_angle_rad_(static_cast<float>(1.0 / calibration.camera.fx)),
      edge_sample_offsets_px_(rankOneLatticeOffsets(options.edge_pixel_samples)) {}

void CityRenderer::setRay(const Eigen::Vector3f& origin, const Eigen::Vector3f& d, int i,
                          RayPacket& rays) const {
  const float ground_z = options_.ground_z_m;
  rays.origin_x[i] = origin.x();
  rays.origin_y[i] = origin.y();
  rays.origin_z[i] = origin.z();
  rays.direction_x[i] = d.x();
  rays.direction_y[i] = d.y();
  rays.direction_z[i] = d.z();
  rays.t_near[i] = 0.0f;
  // The ground plane z = ground_z ends every downward ray within kGroundRange_m:
  // t = (ground_z - o_z) / d_z. A ray that meets it farther off looks at the
  // horizon (it dips less than a microradian below it from a camera metres
  // up), and a point beyond 1.8e18 m is no ray origin Embree takes.
  constexpr float kGroundRange_m = 1e7f;
  const float ground_t = d.z() < 0.0f && origin.z() > ground_z
                             ? (ground_z - origin.z()) / d.z()
                             : std::numeric_limits<float>::infinity();
  rays.t_far[i] = ground_t <= kGroundRange_m ? ground_t : std::numeric_limits<float>::infinity();
  rays.active[i] = d.squaredNorm() > 0.0f;
}

void CityRenderer::intersect(const RayPacket& rays, PacketHits& hits) const {
  caster_.intersect(rays, hits);
  for (int i = 0; i < kRayPacketSize; ++i) {
    if (rays.active[i] && hits.triangle[i] == kNoTriangle && std::isfinite(rays.t_far[i])) {
      hits.triangle[i] = kGroundTriangle;
      hits.t[i] = rays.t_far[i];
    }
  }
}

void CityRenderer::castTile(const Eigen::Matrix3f& R_world_camera, const Eigen::Vector3f& origin,
                            int u0, int v0, RayPacket& rays, PacketHits& hits) const {
  for (int i = 0; i < kRayPacketSize; ++i) {
    const int u = u0 + i % kTileSize;
    const int v = v0 + i / kTileSize;
    const bool inside = u < rays_.width() && v < rays_.height();
    setRay(
        origin,
        inside ? Eigen::Vector3f(R_world_camera * rays_.direction(u, v)) : Eigen::Vector3f::Zero(),
        i, rays);
  }
  intersect(rays, hits);
}

void CityRenderer::storeTile(const RayPacket& rays, const PacketHits& hits, int u0, int v0,
                             PixelHits& pixels) const {
  for (int i = 0; i < kRayPacketSize; ++i) {
    if (rays.active[i]) {
      const size_t index = (v0 + i / kTileSize) * pixels.width + u0 + i % kTileSize;
      pixels.triangle[index] = hits.triangle[i];
      pixels.distance_m[index] = hits.t[i];
    }
  }
}

PixelHits CityRenderer::castPixels(const Eigen::Isometry3d& T_world_camera,
                                   cv::Mat* radiance) const {
  PixelHits pixels = noHits(rays_.width(), rays_.height());
  const Eigen::Matrix3f R = T_world_camera.linear().cast<float>();
  const Eigen::Vector3f origin = T_world_camera.translation().cast<float>();
  RayPacket rays;
  PacketHits hits;
  std::array<float, kRayPacketSize> tile_radiance{};
  for (int v0 = 0; v0 < pixels.height; v0 += kTileSize) {
    for (int u0 = 0; u0 < pixels.width; u0 += kTileSize) {
      castTile(R, origin, u0, v0, rays, hits);
      storeTile(rays, hits, u0, v0, pixels);
      if (radiance == nullptr) {
        continue;
      }
      shadePacket(rays, hits, tile_radiance);
      for (int i = 0; i < kRayPacketSize; ++i) {
        if (rays.active[i]) {
          radiance->at<float>(v0 + i / kTileSize, u0 + i % kTileSize) = tile_radiance[i];
        }
      }
    }
  }
  return pixels;
}

PixelHits CityRenderer::castPrimaryRays(const Eigen::Isometry3d& T_world_camera) const {
  return castPixels(T_world_camera, nullptr);
}

void CityRenderer::shadePacket(const RayPacket& rays, const PacketHits& hits,
                               std::array<float, kRayPacketSize>& radiance) const {
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
    radiance[i] = hits.triangle[i] == kNoTriangle
                      ? shader_.skyRadiance(d)
                      : albedo[i] * shader_.irradiance(normals[i], in_shadow[i]);
  }
}

bool CityRenderer::surfacesDiffer(uint32_t triangle_a, float distance_a_m, uint32_t triangle_b,
                                  float distance_b_m) const {
  if (triangle_a == triangle_b) {
    return false;
  }
  if (triangle_a >= kGroundTriangle || triangle_b >= kGroundTriangle) {
    return true;  // the sky or the ground beside anything else
  }
  const SurfaceTag& a = mesh_.tag(triangle_a);
  const SurfaceTag& b = mesh_.tag(triangle_b);
  if (a.object_id != b.object_id || a.kind != b.kind ||
      mesh_.normal(triangle_a).dot(mesh_.normal(triangle_b)) < kCreaseCosine) {
    return true;
  }
  return std::abs(distance_a_m - distance_b_m) >
         kDepthStepFraction * std::min(distance_a_m, distance_b_m);
}

void CityRenderer::integrateEdgePixels(const Eigen::Matrix3f& R_world_camera,
                                       const Eigen::Vector3f& origin, const PixelHits& pixels,
                                       cv::Mat& radiance) const {
  const int width = pixels.width;
  const int height = pixels.height;
  std::vector<uint8_t> on_edge(pixels.triangle.size(), 0);
  const auto compare = [&](size_t a, size_t b) {
    if (surfacesDiffer(pixels.triangle[a], pixels.distance_m[a], pixels.triangle[b],
                       pixels.distance_m[b])) {
      on_edge[a] = on_edge[b] = 1;
    }
  };
  for (int v = 0; v < height; ++v) {
    for (int u = 0; u < width; ++u) {
      const size_t index = static_cast<size_t>(v) * width + u;
      if (u + 1 < width) {
        compare(index, index + 1);
      }
      if (v + 1 < height) {
        compare(index, index + width);
      }
    }
  }
  RayPacket rays;
  PacketHits hits;
  std::array<float, kRayPacketSize> sample_radiance{};
  const int samples = static_cast<int>(edge_sample_offsets_px_.size());
  for (int i = samples; i < kRayPacketSize; ++i) {
    rays.active[i] = false;
  }
  for (size_t index = 0; index < on_edge.size(); ++index) {
    if (!on_edge[index]) {
      continue;
    }
    const float u = static_cast<float>(index % width);
    const float v = static_cast<float>(index / width);
    for (int k = 0; k < samples; ++k) {
      const Eigen::Vector2f& offset = edge_sample_offsets_px_[k];
      setRay(origin, R_world_camera * rays_.directionAt(u + offset.x(), v + offset.y()), k, rays);
    }
    intersect(rays, hits);
    shadePacket(rays, hits, sample_radiance);
    float sum = 0.0f;
    int active = 0;
    for (int k = 0; k < samples; ++k) {
      if (rays.active[k]) {
        sum += sample_radiance[k];
        ++active;
      }
    }
    if (active > 0) {
      radiance.at<float>(static_cast<int>(v), static_cast<int>(u)) = sum / active;
    }
  }
}

cv::Mat CityRenderer::renderRadiance(const Eigen::Isometry3d& T_world_camera) const {
  cv::Mat radiance(rays_.height(), rays_.width(), CV_32FC1, cv::Scalar(0.0f));
  const PixelHits pixels = castPixels(T_world_camera, &radiance);
  if (edge_sample_offsets_px_.size() > 1) {
    integrateEdgePixels(T_world_camera.linear().cast<float>(),
                        T_world_camera.translation().cast<float>(), pixels, radiance);
  }
  return radiance;
}

int CityRenderer::blurSamples(const Eigen::Isometry3d& T_world_camera_open,
                              const Eigen::Isometry3d& T_world_camera_close) const {
  // Nearest surface a blur is drawn for (m) and the largest spacing of the
  // samples in the image (px).
  constexpr double kNearestDepth_m = 2.0;
  constexpr double kSampleSpacing_px = 0.5;
  const Eigen::AngleAxisd rotation(T_world_camera_open.linear().transpose() *
                                   T_world_camera_close.linear());
  const double translation_m =
      (T_world_camera_close.translation() - T_world_camera_open.translation()).norm();
  const double motion_px = (std::abs(rotation.angle()) + translation_m / kNearestDepth_m) /
                           static_cast<double>(pixel_angle_rad_);
  const double needed = std::ceil(motion_px / kSampleSpacing_px);
  return static_cast<int>(
      std::clamp(needed, 1.0, static_cast<double>(options_.motion_blur_samples)));
}

cv::Mat CityRenderer::renderExposureRadiance(const Eigen::Isometry3d& T_world_camera_open,
                                             const Eigen::Isometry3d& T_world_camera_close,
                                             const cv::Mat& centre_radiance) const {
  const int samples = blurSamples(T_world_camera_open, T_world_camera_close);
  const auto render = [&](int k) {
    const double s = (k + 0.5) / samples;
    return 2 * k + 1 == samples && !centre_radiance.empty()
               ? centre_radiance
               : renderRadiance(interpolate(T_world_camera_open, T_world_camera_close, s));
  };
  if (samples == 1) {
    return render(0);
  }
  cv::Mat radiance = cv::Mat::zeros(rays_.height(), rays_.width(), CV_32FC1);
  for (int k = 0; k < samples; ++k) {
    radiance += render(k);
  }
  radiance /= samples;
  return radiance;
}

cv::Mat CityRenderer::renderImage(const Eigen::Isometry3d& T_world_camera_open,
                                  const Eigen::Isometry3d& T_world_camera_close,
                                  uint64_t noise_seed, float light_fraction) const {
  const cv::Mat radiance = renderExposureRadiance(T_world_camera_open, T_world_camera_close);
  cv::Mat grey = radiance * (255.0f * options_.exposure * light_fraction);
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
