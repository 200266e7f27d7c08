// The façade detail the simulator paints on a building's walls, which the city
// model lacks: storeys of windows (a frame and a central mullion around dark
// glass), on the ground floor a door every few bays, shop fronts or windows
// between, and shop signs above, all drawn from the building's id so that a
// building looks the same from every view.
//
// Laid out in wall coordinates: u runs along the wall,
//   u = (-n_y x + n_x y) / |(n_x, n_y)|
// for a wall with unit normal n through world point (x, y, z), and v = z - base
// runs up from the building's base. Storey k spans v in [k H, (k + 1) H); bay j
// spans u in [j P, (j + 1) P), its window centred in it. Only storeys that end
// below the building's top (plus 0.6 m, for rounded LoD1 heights) get windows.
//
// The shader asks what lies at a point (`at`); the simulator's ground truth
// asks for the borders of the elements (`borders`): the outer and inner edges
// of window and door frames, the mullion's sides and the signs' edges, every
// line where the painted albedo can step.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <vector>

namespace lineloc {

// A straight border in wall coordinates (m).
struct WallBorder {
  Eigen::Vector2d from_uv = Eigen::Vector2d::Zero();
  Eigen::Vector2d to_uv = Eigen::Vector2d::Zero();
};

class FacadeLayout {
 public:
  // The layout of building `object_id` whose base and top are at these heights.
  FacadeLayout(uint32_t object_id, float base_z, float top_z);

  // What is painted at wall coordinates (u, v): the albedo of a window, door
  // or sign there, or of the bare wall (which the shader may texture as brick).
  struct Paint {
    float albedo = 0.0f;
    bool bare_wall = true;
  };
  Paint at(float u, float v) const;

  // The borders of every element whose bay overlaps u in [u_min, u_max] and
  // whose storey starts below v_max. Not every piece of a border is an edge
  // (two signs side by side, a door cutting a sign): the caller keeps the
  // pieces across which `at` differs.
  std::vector<WallBorder> borders(double u_min, double u_max, double v_max) const;

  float wallAlbedo() const { return wall_albedo_; }
  bool brick() const { return brick_; }

  // u of a world point on a wall with unit normal n (see above); x for a
  // horizontal surface.
  static float wallU(const Eigen::Vector3f& point, const Eigen::Vector3f& normal);

 private:
  bool windowsIn(int storey) const;
  bool doorIn(int bay) const;
  bool signIn(int bay) const;

  uint32_t object_id_;
  float base_z_;
  float top_z_;
  float storey_height_m_;
  float window_pitch_m_;
  float window_width_m_;
  float window_height_m_;
  float wall_albedo_;
  bool brick_;
  bool shop_front_;
  bool sign_;
  int door_every_;
};

}  // namespace lineloc
