#include "sim/render/facade_layout.h"

#include <cmath>

#include "sim/render/procedural_hash.h"

namespace lineloc {
namespace {

constexpr float kWindowFrame_m = 0.08f;
constexpr float kWindowSill_m = 0.9f;
constexpr float kDoorWidth_m = 1.1f;
constexpr float kDoorHeight_m = 2.3f;
constexpr float kShopFrontSill_m = 0.35f;
constexpr float kShopFrontHeight_m = 2.1f;
// A sign spans its bay this far below the top of the ground floor, this high.
constexpr float kSignBelowStoreyTop_m = 0.75f;
constexpr float kSignHeight_m = 0.45f;
// Storeys ending this far above the building's top still get windows.
constexpr float kRoofAllowance_m = 0.6f;

float windowAlbedo(float x_in_window, float y_in_window, float width, float height) {
  const bool frame = x_in_window < kWindowFrame_m || width - x_in_window < kWindowFrame_m ||
                     y_in_window < kWindowFrame_m || height - y_in_window < kWindowFrame_m ||
                     std::abs(x_in_window - 0.5f * width) < 0.5f * kWindowFrame_m;
  return frame ? 0.85f : 0.12f + 0.08f * y_in_window / height;
}

uint32_t signedBits(int value) {
  return static_cast<uint32_t>(static_cast<int32_t>(value));
}

void addRectangle(double u0, double v0, double width, double height,
                  std::vector<WallBorder>& borders) {
  const double u1 = u0 + width, v1 = v0 + height;
  borders.push_back({{u0, v0}, {u1, v0}});
  borders.push_back({{u1, v0}, {u1, v1}});
  borders.push_back({{u1, v1}, {u0, v1}});
  borders.push_back({{u0, v1}, {u0, v0}});
}

// Outer and inner edges of the frame, and the mullion's two sides.
void addWindow(double u0, double v0, double width, double height,
               std::vector<WallBorder>& borders) {
  addRectangle(u0, v0, width, height, borders);
  addRectangle(u0 + kWindowFrame_m, v0 + kWindowFrame_m, width - 2.0 * kWindowFrame_m,
               height - 2.0 * kWindowFrame_m, borders);
  for (const double side : {-0.5, 0.5}) {
    const double u = u0 + 0.5 * width + side * kWindowFrame_m;
    borders.push_back({{u, v0}, {u, v0 + height}});
  }
}

}  // namespace

FacadeLayout::FacadeLayout(uint32_t object_id, float base_z, float top_z)
    : object_id_(object_id),
      base_z_(base_z),
      top_z_(top_z),
      storey_height_m_(2.9f + 0.5f * unitFromHash(proceduralHash(object_id, 1))),
      window_pitch_m_(2.2f + 1.2f * unitFromHash(proceduralHash(object_id, 2))),
      window_width_m_(window_pitch_m_ *
                      (0.42f + 0.16f * unitFromHash(proceduralHash(object_id, 3)))),
      window_height_m_(storey_height_m_ *
                       (0.45f + 0.12f * unitFromHash(proceduralHash(object_id, 4)))),
      wall_albedo_(0.32f + 0.3f * unitFromHash(proceduralHash(object_id, 5))),
      brick_(unitFromHash(proceduralHash(object_id, 6)) < 0.65f),
      shop_front_(unitFromHash(proceduralHash(object_id, 7)) < 0.4f),
      sign_(unitFromHash(proceduralHash(object_id, 8)) < 0.5f),
      door_every_(3 + static_cast<int>(proceduralHash(object_id, 9) % 3)) {}

float FacadeLayout::wallU(const Eigen::Vector3f& point, const Eigen::Vector3f& normal) {
  const float horizontal = std::sqrt(normal.x() * normal.x() + normal.y() * normal.y());
  return horizontal > 1e-3f ? (-normal.y() * point.x() + normal.x() * point.y()) / horizontal
                            : point.x();
}

bool FacadeLayout::windowsIn(int storey) const {
  return base_z_ + static_cast<float>(storey + 1) * storey_height_m_ <= top_z_ + kRoofAllowance_m;
}

bool FacadeLayout::doorIn(int bay) const {
  return bay % door_every_ == 0;
}

bool FacadeLayout::signIn(int bay) const {
  return sign_ && proceduralHash(object_id_, signedBits(bay) / 3u) % 2 == 0;
}

FacadeLayout::Paint FacadeLayout::at(float u, float v) const {
  const int storey = static_cast<int>(std::floor(v / storey_height_m_));
  const float v_in_storey = v - static_cast<float>(storey) * storey_height_m_;
  const float bay_start = std::floor(u / window_pitch_m_);
  const int bay = static_cast<int>(bay_start);
  const float u_in_bay = u - bay_start * window_pitch_m_;
  const float x_in_window = u_in_bay - 0.5f * (window_pitch_m_ - window_width_m_);
  const bool in_window_column = x_in_window >= 0.0f && x_in_window < window_width_m_;
  if (storey == 0) {
    const bool door = doorIn(bay);
    const float door_x = u_in_bay - 0.5f * (window_pitch_m_ - kDoorWidth_m);
    if (door && door_x >= 0.0f && door_x < kDoorWidth_m && v < kDoorHeight_m) {
      const bool frame = door_x < kWindowFrame_m || kDoorWidth_m - door_x < kWindowFrame_m;
      return {frame ? 0.8f : 0.18f, false};
    }
    const float sign_bottom = storey_height_m_ - kSignBelowStoreyTop_m;
    if (v_in_storey > sign_bottom && v_in_storey < sign_bottom + kSignHeight_m && signIn(bay)) {
      return {0.92f, false};
    }
    const float height = shop_front_ ? kShopFrontHeight_m : window_height_m_;
    const float sill = shop_front_ ? kShopFrontSill_m : kWindowSill_m;
    if (!door && windowsIn(storey) && in_window_column && v_in_storey > sill &&
        v_in_storey < sill + height) {
      return {windowAlbedo(x_in_window, v_in_storey - sill, window_width_m_, height), false};
    }
  } else if (windowsIn(storey) && in_window_column && v_in_storey > kWindowSill_m &&
             v_in_storey < kWindowSill_m + window_height_m_) {
    return {
        windowAlbedo(x_in_window, v_in_storey - kWindowSill_m, window_width_m_, window_height_m_),
        false};
  }
  return {wall_albedo_, true};
}

std::vector<WallBorder> FacadeLayout::borders(double u_min, double u_max, double v_max) const {
  std::vector<WallBorder> borders;
  const double pitch = window_pitch_m_, storey_height = storey_height_m_;
  const int first_bay = static_cast<int>(std::floor(u_min / pitch));
  const int last_bay = static_cast<int>(std::floor(u_max / pitch));
  const double window_offset = 0.5 * (pitch - window_width_m_);
  for (int bay = first_bay; bay <= last_bay; ++bay) {
    const double bay_start = bay * pitch;
    for (int storey = 0; storey * storey_height < v_max; ++storey) {
      const double storey_start = storey * storey_height;
      if (storey > 0) {
        if (windowsIn(storey)) {
          addWindow(bay_start + window_offset, storey_start + kWindowSill_m, window_width_m_,
                    window_height_m_, borders);
        }
        continue;
      }
      if (doorIn(bay)) {
        const double door_start = bay_start + 0.5 * (pitch - kDoorWidth_m);
        addRectangle(door_start, 0.0, kDoorWidth_m, kDoorHeight_m, borders);
        for (const double inset : {kWindowFrame_m, kDoorWidth_m - kWindowFrame_m}) {
          borders.push_back({{door_start + inset, 0.0}, {door_start + inset, kDoorHeight_m}});
        }
      } else if (windowsIn(0)) {
        addWindow(bay_start + window_offset, shop_front_ ? kShopFrontSill_m : kWindowSill_m,
                  window_width_m_, shop_front_ ? kShopFrontHeight_m : window_height_m_, borders);
      }
      if (signIn(bay)) {
        addRectangle(bay_start, storey_height - kSignBelowStoreyTop_m, pitch, kSignHeight_m,
                     borders);
      }
    }
  }
  return borders;
}

}  // namespace lineloc
