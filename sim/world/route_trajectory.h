// A ground robot driving a street route: the waypoint polyline smoothed into
// a uniform cubic B-spline (curvature-continuous, so yaw rate and lateral
// acceleration have no steps) through control points every few metres, driven
// with a speed profile of quintic smoothstep ramps s(u) = 6u^5 - 15u^4 + 10u^3
// between random cruise speeds (each capped by the bends it drives through),
// with stops, from standing or from an initial speed v0. Distance along the
// path is the closed-form integral of the speed, v0 t plus the ramps'
// (S(u) = u^6 - 3u^5 + 5u^4/2); arclength is inverted by Newton's method on
// the spline parameter. The robot rides the ground: its height over the
// arclength s of the path is h(s), the uniform cubic B-spline through the
// ground's heights at most a control spacing apart along the path, straight
// at its ends (a sloping street, smoothed over a few metres as wheels and
// suspension do), and it pitches with the grade, theta = atan h'(s), without
// rolling. With v the speed over the ground's plan, unit tangent T, left
// normal N, signed curvature k and yaw psi,
//   v_world = (v T, h' v),  a_world = (v' T + k v^2 N, h'' v^2 + h' v'),
//   R = Rz(psi) Ry(-theta),  psi' = k v,  theta' = h'' v / (1 + h'^2),
//   omega_body = (sin(theta) psi', -theta', cos(theta) psi'),
// and the specific force is R^T (a + g z); on level ground theta = 0.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <functional>
#include <vector>

#include "sim/sensors/ground_truth_trajectory.h"

namespace lineloc {

struct RouteDriveOptions {
  int64_t start_stamp_ns = 1'700'000'000'000'000'000;
  double duration_s = 60.0;
  // Standing still at the start, so the IMU can be aligned (s).
  double initial_still_s = 5.0;
  // Speed at the start (m/s): 0 starts standing, above 0 (up to max_speed_m_s,
  // with initial_still_s 0) starts driving at it along the route.
  double initial_speed_m_s = 0.0;
  double min_speed_m_s = 0.5;
  double max_speed_m_s = 2.0;
  // Each leg's cruise speed is capped so that k v^2 stays below this on the
  // sharpest bend it drives (m/s^2).
  double max_lateral_acceleration_m_s2 = 1.0;
  double ramp_s = 2.0;
  double min_leg_s = 4.0;
  double max_leg_s = 12.0;
  double stop_probability = 0.2;
  double min_stop_s = 2.0;
  double max_stop_s = 5.0;
  // Spacing of the spline's control points along the route (m).
  double control_spacing_m = 5.0;
  // Height of the body frame above the ground under it (m).
  double body_height_m = 0.3;
  double gravity_m_s2 = 9.80665;
  uint64_t seed = 1;
};

class RouteTrajectory : public sim::TruthTrajectory {
 public:
  // `waypoints` in the world frame, `ground_height_m` the ground's height
  // under a point of them (m, world z). Throws
  // std::invalid_argument when the route is shorter than one control spacing
  // or the options are inconsistent.
  RouteTrajectory(const std::vector<Eigen::Vector2d>& waypoints,
                  const std::function<double(const Eigen::Vector2d&)>& ground_height_m,
                  const RouteDriveOptions& options);

  sim::TruthSample at(int64_t stamp_ns) const override;
  int64_t startStamp_ns() const override { return options_.start_stamp_ns; }
  int64_t endStamp_ns() const override;
  // Arclength of the smoothed path (m).
  double pathLength() const { return arclength_.back(); }

 private:
  struct Ramp {
    double start_s;
    double duration_s;
    double change_m_s;
  };
  struct SplinePoint {
    Eigen::Vector2d position;
    Eigen::Vector2d first;   // d/dU
    Eigen::Vector2d second;  // d2/dU2
  };

  void planSpeed();
  double speed(double t) const;
  double acceleration(double t) const;
  double distance(double t) const;
  SplinePoint spline(double U) const;
  // h(s), h'(s) and h''(s) at arclength s.
  Eigen::Vector3d groundHeight(double arclength_m) const;
  double parameterAt(double arclength_m) const;
  // Largest curvature between two arclengths (1/m).
  double maxCurvature(double from_m, double to_m) const;

  RouteDriveOptions options_;
  // Control values of h, whose knots lie at arclengths 0, d, 2d, .. the
  // path's end (d at most the control spacing), with one more at each end.
  std::vector<double> ground_control_m_;
  double ground_spacing_m_ = 0.0;
  std::vector<Eigen::Vector2d> control_;
  // Arclength at U = 0, h, 2h, ... (h = kTableStep).
  std::vector<double> arclength_;
  // Unsigned curvature at the same parameters (1/m).
  std::vector<double> curvature_;
  std::vector<Ramp> ramps_;
};

}  // namespace lineloc
