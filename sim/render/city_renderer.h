// Renders what a calibrated camera sees of a SceneMesh standing on a flat
// ground plane under a sky: one primary ray per pixel through the exact lens
// model (CameraRays, inverse mapping of OpenCV's distortion), Embree packets of
// 4x4 pixels, procedural surface detail and sun shading (SurfaceShader), an
// optional shadow ray towards the sun, optional motion blur (the mean of
// renders at poses spread over the exposure), and Gaussian sensor noise.
#pragma once

#include <Eigen/Geometry>
#include <cstdint>
#include <opencv2/core.hpp>
#include <vector>

#include "common/camera/camera_calibration.h"
#include "sim/render/camera_rays.h"
#include "sim/render/ray_caster.h"
#include "sim/render/surface_shader.h"

namespace lineloc {

struct RenderOptions {
  ShadingOptions shading;
  // Height of the ground plane (m, world z).
  float ground_z_m = 0.0f;
  // Cast a shadow ray per sunlit pixel.
  bool shadows = true;
  // Image value = 255 * exposure * radiance.
  float exposure = 1.0f;
  // Standard deviation of the additive Gaussian sensor noise (grey levels).
  float noise_sigma = 2.0f;
  // Renders averaged over the exposure; 1 = no motion blur.
  int motion_blur_samples = 1;
};

// What every pixel's ray hits first: a SceneMesh triangle, the ground plane
// (kGroundTriangle) or nothing (kNoTriangle, the sky; distance infinite).
inline constexpr uint32_t kGroundTriangle = kNoTriangle - 1;

struct PixelHits {
  int width = 0;
  int height = 0;
  std::vector<uint32_t> triangle;
  std::vector<float> distance_m;
};

class CityRenderer {
 public:
  // Throws std::invalid_argument for a non-positive exposure, negative noise,
  // fewer than 1 motion-blur sample, or a camera CameraRays rejects.
  CityRenderer(const SceneMesh& mesh, const CameraCalibration& calibration,
               const RenderOptions& options);

  // The first surface along every pixel's ray.
  PixelHits castPrimaryRays(const Eigen::Isometry3d& T_world_camera) const;
  // Noise-free radiance (CV_32FC1, 1 = white) seen from one pose.
  cv::Mat renderRadiance(const Eigen::Isometry3d& T_world_camera) const;
  // The 8-bit grey image exposed while the camera moves from T_world_camera_open
  // to T_world_camera_close (equal poses: no blur); the noise is drawn from
  // `noise_seed`, so equal inputs give equal bytes.
  cv::Mat renderImage(const Eigen::Isometry3d& T_world_camera_open,
                      const Eigen::Isometry3d& T_world_camera_close, uint64_t noise_seed) const;

  const CameraRays& rays() const { return rays_; }

 private:
  // Casts the rays of the 4x4 tile with top-left pixel (u0, v0).
  void castTile(const Eigen::Matrix3f& R_world_camera, const Eigen::Vector3f& origin, int u0,
                int v0, RayPacket& rays, PacketHits& hits) const;
  void shadeTile(const RayPacket& rays, const PacketHits& hits, int u0, int v0,
                 cv::Mat& radiance) const;

  SceneMesh mesh_;
  RenderOptions options_;
  CameraRays rays_;
  RayCaster caster_;
  SurfaceShader shader_;
  // Angle subtended by one pixel (rad), 1 / fx: footprint = distance * angle.
  float pixel_angle_rad_ = 0.0f;
};

}  // namespace lineloc
