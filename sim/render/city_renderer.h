// Renders what a calibrated camera sees of a SceneMesh standing on a flat
// ground plane under a sky: one primary ray per pixel through the exact lens
// model (CameraRays, inverse mapping of OpenCV's distortion), Embree packets of
// 4x4 pixels, procedural surface detail and sun shading (SurfaceShader), an
// optional shadow ray towards the sun, optional motion blur (the mean of
// renders at poses spread over the exposure), and, for an ideal camera,
// Gaussian noise of one sigma over the image (CameraSensor models a real one).
//
// A sensor's pixel integrates the light over its area; one ray at its centre
// puts every edge on a pixel boundary, up to half a pixel from where it is. A
// level camera sees a building's vertical edge as a vertical line, every row
// off by the same amount, so nothing averages the error away along it, and
// 0.3 px on a corner 30 m ahead and 6 m aside moves a pose 8 cm along the
// street (du = f x dz / z^2). So every pixel that a geometric edge crosses
// (its neighbours see the sky, the ground, another object, a face turned
// another way or one behind it) is the mean of edge_pixel_samples rays spread
// over it on a rank-1 lattice, x_k = (k + 1/2) / n, y_k = frac((k g + 1/2) / n),
// g chosen once for the largest distance between points (Dammertz & Keller,
// "Image synthesis by rank-1 lattices", MCQMC 2006): n distinct columns and
// rows, so a vertical or horizontal edge is placed to 1/n px. Texture edges
// (windows, brick courses) and shadow boundaries keep one ray: the model holds
// none of them.
#pragma once

#include <Eigen/Geometry>
#include <array>
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
  // At most this many renders averaged over the exposure; 1 = no motion blur.
  int motion_blur_samples = 1;
  // Rays averaged over each pixel a geometric edge crosses, 1 to
  // kRayPacketSize; 1 = one ray per pixel centre everywhere.
  int edge_pixel_samples = 16;
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
  // fewer than 1 motion-blur sample, edge_pixel_samples outside 1 to
  // kRayPacketSize, or a camera CameraRays rejects.
  CityRenderer(const SceneMesh& mesh, const CameraCalibration& calibration,
               const RenderOptions& options);

  // The first surface along every pixel's ray.
  PixelHits castPrimaryRays(const Eigen::Isometry3d& T_world_camera) const;
  // Noise-free radiance (CV_32FC1, 1 = white) seen from one pose, edge pixels
  // integrated over their area.
  cv::Mat renderRadiance(const Eigen::Isometry3d& T_world_camera) const;
  // The mean radiance over an exposure while the camera moves from
  // T_world_camera_open to T_world_camera_close: n renders at the poses
  // (k + 1/2) / n of the way, n = clamp(ceil(d / 0.5 px), 1,
  // motion_blur_samples) for the image motion bound d = (theta + |dt| / 2 m) fx,
  // theta the rotation and dt the translation over the exposure (a point
  // 2 m away or further moves at most that far), so samples lie at most half
  // a pixel apart. `centre_radiance`, when given, is the render at the
  // halfway pose, which an odd count includes.
  cv::Mat renderExposureRadiance(const Eigen::Isometry3d& T_world_camera_open,
                                 const Eigen::Isometry3d& T_world_camera_close,
                                 const cv::Mat& centre_radiance = cv::Mat()) const;
  // The ideal camera's 8-bit grey image of that exposure,
  // 255 x exposure x light_fraction x radiance + N(0, noise_sigma^2), with
  // light_fraction the share of the scene's light that reaches the sensor (a
  // LensCover's open fraction); the noise is drawn from `noise_seed`, so equal
  // inputs give equal bytes.
  cv::Mat renderImage(const Eigen::Isometry3d& T_world_camera_open,
                      const Eigen::Isometry3d& T_world_camera_close, uint64_t noise_seed,
                      float light_fraction = 1.0f) const;

  const CameraRays& rays() const { return rays_; }
  // The n above.
  int blurSamples(const Eigen::Isometry3d& T_world_camera_open,
                  const Eigen::Isometry3d& T_world_camera_close) const;

 private:
  // Ray i of a packet: from origin along world direction d (zero: inactive),
  // ended by the ground plane.
  void setRay(const Eigen::Vector3f& origin, const Eigen::Vector3f& d, int i,
              RayPacket& rays) const;
  // First hits of a packet, the ground plane's included.
  void intersect(const RayPacket& rays, PacketHits& hits) const;
  // Casts the rays of the 4x4 tile with top-left pixel (u0, v0).
  void castTile(const Eigen::Matrix3f& R_world_camera, const Eigen::Vector3f& origin, int u0,
                int v0, RayPacket& rays, PacketHits& hits) const;
  // Stores a tile's hits in `pixels`.
  void storeTile(const RayPacket& rays, const PacketHits& hits, int u0, int v0,
                 PixelHits& pixels) const;
  // Casts every pixel's primary ray, tile by tile, and shades each tile into
  // `radiance` (CV_32FC1, the image's size) unless it is null.
  PixelHits castPixels(const Eigen::Isometry3d& T_world_camera, cv::Mat* radiance) const;
  // Radiance along each active ray of a packet.
  void shadePacket(const RayPacket& rays, const PacketHits& hits,
                   std::array<float, kRayPacketSize>& radiance) const;
  // True when two hits lie on different surfaces (see the header comment).
  bool surfacesDiffer(uint32_t triangle_a, float distance_a_m, uint32_t triangle_b,
                      float distance_b_m) const;
  // Replaces each edge pixel of `radiance` by the mean over its area.
  void integrateEdgePixels(const Eigen::Matrix3f& R_world_camera, const Eigen::Vector3f& origin,
                           const PixelHits& pixels, cv::Mat& radiance) const;

  SceneMesh mesh_;
  RenderOptions options_;
  CameraRays rays_;
  RayCaster caster_;
  SurfaceShader shader_;
  // Angle subtended by one pixel (rad), 1 / fx: footprint = distance * angle.
  float pixel_angle_rad_ = 0.0f;
  // Edge pixels' sample points relative to the pixel centre (px).
  std::vector<Eigen::Vector2f> edge_sample_offsets_px_;
};

}  // namespace lineloc
