// What the camera sees on each surface: procedural albedo for the detail a city
// model lacks (windows, doors, brick courses, shop signs on façades; asphalt;
// cars, trees, poles, people), a sky gradient, and Lambertian sun shading
//   L = albedo (ambient + (1 - ambient) max(0, n . s) lit),
// with s the unit vector towards the sun and lit = 0 in shadow.
//
// Texture detail finer than a pixel fades out (contrast scaled by
// clamp(2 - 4 footprint / period, 0, 1), zero at the Nyquist period), so a
// single ray per pixel does not alias brick courses into moiré lines.
#pragma once

#include <Eigen/Core>

#include "sim/render/scene_mesh.h"

namespace lineloc {

struct ShadingOptions {
  // Unit vector from the scene towards the sun, world frame (z up).
  Eigen::Vector3f sun_direction = Eigen::Vector3f(0.55f, -0.45f, 0.70f).normalized();
  // Fraction of the light that reaches surfaces facing away or in shadow.
  float ambient = 0.35f;
  // False: walls are bare, each its building's one albedo, with no windows,
  // doors, signs or brick (an object model's painted faces).
  bool facade_detail = true;
};

class SurfaceShader {
 public:
  explicit SurfaceShader(const ShadingOptions& options);

  // Albedo in [0, 1] of a mesh surface at world point p with unit normal n;
  // footprint_m is the size of one pixel on the surface.
  float meshAlbedo(const SurfaceTag& tag, const Eigen::Vector3f& p, const Eigen::Vector3f& n,
                   float footprint_m) const;
  // Albedo of the ground plane (asphalt) at world point p.
  float groundAlbedo(const Eigen::Vector3f& p, float footprint_m) const;
  // Radiance of the sky seen along unit direction d.
  float skyRadiance(const Eigen::Vector3f& d) const;
  // Light factor for a surface with unit normal n (facing the viewer).
  float irradiance(const Eigen::Vector3f& n, bool in_shadow) const;
  // True when a surface with this normal faces the sun (worth a shadow ray).
  bool facesSun(const Eigen::Vector3f& n) const { return n.dot(options_.sun_direction) > 0.0f; }
  const Eigen::Vector3f& sunDirection() const { return options_.sun_direction; }

 private:
  float facadeAlbedo(const SurfaceTag& tag, const Eigen::Vector3f& p, const Eigen::Vector3f& n,
                     float footprint_m) const;

  ShadingOptions options_;
};

}  // namespace lineloc
