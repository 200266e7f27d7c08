#include "sim/render/surface_shader.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "sim/render/facade_layout.h"
#include "sim/render/procedural_hash.h"

namespace lineloc {
namespace {

// Brick course: 65 mm brick + 10 mm mortar; brick length 210 mm + 10 mm joint.
constexpr float kCourseHeight_m = 0.075f;
constexpr float kBrickLength_m = 0.22f;
constexpr float kMortarFraction = 0.14f;
constexpr float kGroundGrain_m = 0.12f;
constexpr float kGroundPatch_m = 1.6f;
constexpr float kFoliageCell_m = 0.3f;

// Smooth value noise in [0, 1): lattice hashes blended with smoothstep, so
// the ground has stains but no straight edges for a line detector to find.
float valueNoise(float x, float y, float cell_m, uint32_t salt) {
  const float gx = x / cell_m;
  const float gy = y / cell_m;
  const float fx = std::floor(gx);
  const float fy = std::floor(gy);
  const auto ix = static_cast<uint32_t>(static_cast<int32_t>(fx));
  const auto iy = static_cast<uint32_t>(static_cast<int32_t>(fy));
  const float sx = (gx - fx) * (gx - fx) * (3.0f - 2.0f * (gx - fx));
  const float sy = (gy - fy) * (gy - fy) * (3.0f - 2.0f * (gy - fy));
  const float bottom = unitFromHash(proceduralHash(ix, iy, salt)) * (1.0f - sx) +
                       unitFromHash(proceduralHash(ix + 1, iy, salt)) * sx;
  const float top = unitFromHash(proceduralHash(ix, iy + 1, salt)) * (1.0f - sx) +
                    unitFromHash(proceduralHash(ix + 1, iy + 1, salt)) * sx;
  return bottom * (1.0f - sy) + top * sy;
}

// Contrast kept for a pattern of the given period seen at this pixel footprint.
float detailContrast(float footprint_m, float period_m) {
  return std::clamp(2.0f - 4.0f * footprint_m / period_m, 0.0f, 1.0f);
}

float brickAlbedo(float wall, float u, float v, float footprint_m) {
  const float course = v / kCourseHeight_m;
  const float row = std::floor(course);
  const float stagger = std::fmod(row, 2.0f) == 0.0f ? 0.0f : 0.5f;
  const float along = u / kBrickLength_m + stagger;
  const bool mortar = course - row < kMortarFraction || along - std::floor(along) < 0.05f;
  const float contrast = detailContrast(footprint_m, kCourseHeight_m);
  const float brick_shade =
      0.9f +
      0.2f * unitFromHash(proceduralHash(latticeCell(u + stagger * kBrickLength_m, kBrickLength_m),
                                         static_cast<uint32_t>(static_cast<int32_t>(row))));
  const float detail = mortar ? 1.35f : brick_shade;
  return wall * (1.0f + contrast * (detail - 1.0f));
}

}  // namespace

SurfaceShader::SurfaceShader(const ShadingOptions& options) : options_(options) {
  const float norm = options_.sun_direction.norm();
  if (!(std::abs(norm - 1.0f) < 1e-3f) || !(options_.ambient >= 0.0f && options_.ambient <= 1.0f)) {
    throw std::invalid_argument(fmt::format(
        "SurfaceShader: sun direction must be a unit vector (norm {}) and ambient in [0, 1] ({})",
        norm, options_.ambient));
  }
}

float SurfaceShader::facadeAlbedo(const SurfaceTag& tag, const Eigen::Vector3f& p,
                                  const Eigen::Vector3f& n, float footprint_m) const {
  const FacadeLayout layout(tag.object_id, tag.base_z, tag.top_z);
  if (!options_.facade_detail) {
    return layout.wallAlbedo();
  }
  const float u = FacadeLayout::wallU(p, n);
  const float v = p.z() - tag.base_z;
  const FacadeLayout::Paint paint = layout.at(u, v);
  return paint.bare_wall && layout.brick() ? brickAlbedo(paint.albedo, u, v, footprint_m)
                                           : paint.albedo;
}

float SurfaceShader::meshAlbedo(const SurfaceTag& tag, const Eigen::Vector3f& p,
                                const Eigen::Vector3f& n, float footprint_m) const {
  const uint32_t id = tag.object_id;
  switch (tag.kind) {
    case SurfaceKind::kGround:
      return groundAlbedo(p, footprint_m);
    case SurfaceKind::kWall:
      return facadeAlbedo(tag, p, n, footprint_m);
    case SurfaceKind::kRoof:
      return 0.22f;
    case SurfaceKind::kCarBody:
      return 0.1f + 0.7f * unitFromHash(proceduralHash(id, 11));
    case SurfaceKind::kCarWindow:
      return 0.08f;
    case SurfaceKind::kTreeTrunk:
      return 0.2f;
    case SurfaceKind::kFoliage: {
      const float contrast = detailContrast(footprint_m, kFoliageCell_m);
      return 0.2f + 0.12f * contrast *
                        (unitFromHash(proceduralHash(latticeCell(p.x(), kFoliageCell_m),
                                                     latticeCell(p.y(), kFoliageCell_m),
                                                     latticeCell(p.z(), kFoliageCell_m))) -
                         0.5f);
    }
    case SurfaceKind::kPole:
      return 0.45f;
    case SurfaceKind::kPerson:
      return 0.1f + 0.5f * unitFromHash(proceduralHash(id, 12));
    case SurfaceKind::kCable:
      return 0.06f;
    case SurfaceKind::kRoadMarking:
      return 0.75f;
    case SurfaceKind::kKerb:
      return 0.42f;
  }
  return 0.5f;
}

float SurfaceShader::groundAlbedo(const Eigen::Vector3f& p, float footprint_m) const {
  const float stains = valueNoise(p.x(), p.y(), kGroundPatch_m, 77) - 0.5f;
  const float grain = valueNoise(p.x(), p.y(), kGroundGrain_m, 78) - 0.5f;
  return 0.3f + 0.06f * stains + 0.06f * detailContrast(footprint_m, kGroundGrain_m) * grain;
}

float SurfaceShader::skyRadiance(const Eigen::Vector3f& d) const {
  // Brightest at the horizon, deeper blue (darker in grey) towards the zenith.
  return 0.95f - 0.3f * std::clamp(d.z(), 0.0f, 1.0f);
}

float SurfaceShader::irradiance(const Eigen::Vector3f& n, bool in_shadow) const {
  const float sun = in_shadow ? 0.0f : std::max(0.0f, n.dot(options_.sun_direction));
  return options_.ambient + (1.0f - options_.ambient) * sun;
}

}  // namespace lineloc
