#include "sim/render/surface_shader.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace lineloc {
namespace {

// Brick course: 65 mm brick + 10 mm mortar; brick length 210 mm + 10 mm joint.
constexpr float kCourseHeight_m = 0.075f;
constexpr float kBrickLength_m = 0.22f;
constexpr float kMortarFraction = 0.14f;
constexpr float kWindowFrame_m = 0.08f;
constexpr float kWindowSill_m = 0.9f;
constexpr float kDoorWidth_m = 1.1f;
constexpr float kDoorHeight_m = 2.3f;
constexpr float kGroundGrain_m = 0.12f;
constexpr float kGroundPatch_m = 1.6f;
constexpr float kFoliageCell_m = 0.3f;

// A well-mixed 32-bit hash (Wellons' lowbias32) of up to three integers.
uint32_t hash(uint32_t a, uint32_t b = 0, uint32_t c = 0) {
  uint32_t x = a * 0x9E3779B1u ^ (b + 0x7F4A7C15u) * 0x85EBCA77u ^ (c + 0x165667B1u) * 0xC2B2AE3Du;
  x ^= x >> 16;
  x *= 0x7FEB352Du;
  x ^= x >> 15;
  x *= 0x846CA68Bu;
  x ^= x >> 16;
  return x;
}

// Uniform in [0, 1) from a hash.
float unit(uint32_t h) {
  return static_cast<float>(h >> 8) * (1.0f / 16777216.0f);
}

uint32_t cell(float coordinate, float size) {
  return static_cast<uint32_t>(static_cast<int32_t>(std::floor(coordinate / size)));
}

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
  const float bottom = unit(hash(ix, iy, salt)) * (1.0f - sx) + unit(hash(ix + 1, iy, salt)) * sx;
  const float top =
      unit(hash(ix, iy + 1, salt)) * (1.0f - sx) + unit(hash(ix + 1, iy + 1, salt)) * sx;
  return bottom * (1.0f - sy) + top * sy;
}

// Contrast kept for a pattern of the given period seen at this pixel footprint.
float detailContrast(float footprint_m, float period_m) {
  return std::clamp(2.0f - 4.0f * footprint_m / period_m, 0.0f, 1.0f);
}

// Façade layout of one building, drawn once per shaded point from its id.
struct FacadeStyle {
  float storey_height_m;
  float window_pitch_m;
  float window_width_m;
  float window_height_m;
  float wall_albedo;
  bool brick;
  bool shop_front;
  bool sign;
  int door_every;

  explicit FacadeStyle(uint32_t id)
      : storey_height_m(2.9f + 0.5f * unit(hash(id, 1))),
        window_pitch_m(2.2f + 1.2f * unit(hash(id, 2))),
        window_width_m(window_pitch_m * (0.42f + 0.16f * unit(hash(id, 3)))),
        window_height_m(storey_height_m * (0.45f + 0.12f * unit(hash(id, 4)))),
        wall_albedo(0.32f + 0.3f * unit(hash(id, 5))),
        brick(unit(hash(id, 6)) < 0.65f),
        shop_front(unit(hash(id, 7)) < 0.4f),
        sign(unit(hash(id, 8)) < 0.5f),
        door_every(3 + static_cast<int>(hash(id, 9) % 3)) {}
};

float brickAlbedo(float wall, float u, float v, float footprint_m) {
  const float course = v / kCourseHeight_m;
  const float row = std::floor(course);
  const float stagger = std::fmod(row, 2.0f) == 0.0f ? 0.0f : 0.5f;
  const float along = u / kBrickLength_m + stagger;
  const bool mortar = course - row < kMortarFraction || along - std::floor(along) < 0.05f;
  const float contrast = detailContrast(footprint_m, kCourseHeight_m);
  const float brick_shade =
      0.9f + 0.2f * unit(hash(cell(u + stagger * kBrickLength_m, kBrickLength_m),
                              static_cast<uint32_t>(static_cast<int32_t>(row))));
  const float detail = mortar ? 1.35f : brick_shade;
  return wall * (1.0f + contrast * (detail - 1.0f));
}

float windowAlbedo(float x_in_window, float y_in_window, float width, float height) {
  const bool frame = x_in_window < kWindowFrame_m || width - x_in_window < kWindowFrame_m ||
                     y_in_window < kWindowFrame_m || height - y_in_window < kWindowFrame_m ||
                     std::abs(x_in_window - 0.5f * width) < 0.5f * kWindowFrame_m;
  return frame ? 0.85f : 0.12f + 0.08f * y_in_window / height;
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
  const FacadeStyle style(tag.object_id);
  // u runs horizontally along the wall, v up from the building's base.
  const float horizontal = std::sqrt(n.x() * n.x() + n.y() * n.y());
  const float u = horizontal > 1e-3f ? (-n.y() * p.x() + n.x() * p.y()) / horizontal : p.x();
  const float v = p.z() - tag.base_z;
  const int storey = static_cast<int>(std::floor(v / style.storey_height_m));
  const float v_in_storey = v - storey * style.storey_height_m;
  const float column = std::floor(u / style.window_pitch_m);
  const float u_in_pitch = u - column * style.window_pitch_m;
  const float x_in_window = u_in_pitch - 0.5f * (style.window_pitch_m - style.window_width_m);
  // A storey gets windows when it ends below the roof line (LoD1 heights are
  // rounded, so allow a little).
  const bool below_roof = tag.base_z + (storey + 1) * style.storey_height_m <= tag.top_z + 0.6f;
  if (storey == 0) {
    const bool door = static_cast<int>(column) % style.door_every == 0;
    const float door_x = u_in_pitch - 0.5f * (style.window_pitch_m - kDoorWidth_m);
    if (door && door_x >= 0.0f && door_x < kDoorWidth_m && v < kDoorHeight_m) {
      return door_x < kWindowFrame_m || kDoorWidth_m - door_x < kWindowFrame_m ? 0.8f : 0.18f;
    }
    const float sign_bottom = style.storey_height_m - 0.75f;
    if (style.sign && v_in_storey > sign_bottom && v_in_storey < sign_bottom + 0.45f &&
        hash(tag.object_id, static_cast<uint32_t>(static_cast<int32_t>(column)) / 3u) % 2 == 0) {
      return 0.92f;
    }
    const float shop_height = style.shop_front ? 2.1f : style.window_height_m;
    const float shop_sill = style.shop_front ? 0.35f : kWindowSill_m;
    if (!door && below_roof && x_in_window >= 0.0f && x_in_window < style.window_width_m &&
        v_in_storey > shop_sill && v_in_storey < shop_sill + shop_height) {
      return windowAlbedo(x_in_window, v_in_storey - shop_sill, style.window_width_m, shop_height);
    }
  } else if (below_roof && x_in_window >= 0.0f && x_in_window < style.window_width_m &&
             v_in_storey > kWindowSill_m && v_in_storey < kWindowSill_m + style.window_height_m) {
    return windowAlbedo(x_in_window, v_in_storey - kWindowSill_m, style.window_width_m,
                        style.window_height_m);
  }
  return style.brick ? brickAlbedo(style.wall_albedo, u, v, footprint_m) : style.wall_albedo;
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
      return 0.1f + 0.7f * unit(hash(id, 11));
    case SurfaceKind::kCarWindow:
      return 0.08f;
    case SurfaceKind::kTreeTrunk:
      return 0.2f;
    case SurfaceKind::kFoliage: {
      const float contrast = detailContrast(footprint_m, kFoliageCell_m);
      return 0.2f + 0.12f * contrast *
                        (unit(hash(cell(p.x(), kFoliageCell_m), cell(p.y(), kFoliageCell_m),
                                   cell(p.z(), kFoliageCell_m))) -
                         0.5f);
    }
    case SurfaceKind::kPole:
      return 0.45f;
    case SurfaceKind::kPerson:
      return 0.1f + 0.5f * unit(hash(id, 12));
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
