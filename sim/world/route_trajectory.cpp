#include "sim/world/route_trajectory.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <random>
#include <stdexcept>

namespace lineloc {
namespace {

constexpr double kTableStep = 0.02;  // spline parameter step of the arclength table
constexpr int kNewtonIterations = 8;
// 5-point Gauss-Legendre nodes and weights on [-1, 1].
constexpr double kGaussNodes[5] = {0.0, -0.5384693101056831, 0.5384693101056831,
                                   -0.9061798459386640, 0.9061798459386640};
constexpr double kGaussWeights[5] = {0.5688888888888889, 0.4786286704993665, 0.4786286704993665,
                                     0.2369268850561891, 0.2369268850561891};

double smoothstep(double u) {
  return u * u * u * (10.0 + u * (-15.0 + 6.0 * u));
}
double smoothstepRate(double u) {
  return 30.0 * u * u * (1.0 - u) * (1.0 - u);
}
double smoothstepIntegral(double u) {
  return u * u * u * u * (2.5 + u * (-3.0 + u));
}

// Control points every `spacing` metres along the polyline, the ends doubled:
// the spline starts and ends a sixth of a spacing inside them, with a
// non-zero tangent (tripled ends would reach them with a zero tangent).
std::vector<Eigen::Vector2d> resample(const std::vector<Eigen::Vector2d>& waypoints,
                                      double spacing) {
  std::vector<Eigen::Vector2d> points{waypoints.front(), waypoints.front()};
  double carried = 0.0;
  for (size_t i = 1; i < waypoints.size(); ++i) {
    const Eigen::Vector2d from = waypoints[i - 1];
    const double length = (waypoints[i] - from).norm();
    const Eigen::Vector2d direction = (waypoints[i] - from) / std::max(length, 1e-12);
    double at = spacing - carried;
    for (; at <= length; at += spacing) {
      points.push_back(from + at * direction);
    }
    carried = length - (at - spacing);
  }
  points.push_back(waypoints.back());
  points.push_back(waypoints.back());
  return points;
}

// The control values c_0..c_n of the uniform cubic B-spline through `heights`
// at its knots with no curvature at its ends: (c_{k-1} + 4 c_k + c_{k+1}) / 6
// = z_k with c_{-1} = 2 c_0 - c_1 and c_{n+1} = 2 c_n - c_{n-1}, so c_0 = z_0
// and c_n = z_n, and the rows between form a diagonally dominant tridiagonal
// system, solved by the Thomas algorithm.
std::vector<double> interpolatingControls(const std::vector<double>& heights) {
  const size_t n = heights.size();
  std::vector<double> controls(heights);
  if (n < 3) {
    return controls;
  }
  constexpr double kDiagonal = 4.0 / 6.0;
  constexpr double kOff = 1.0 / 6.0;
  std::vector<double> upper(n, 0.0);
  std::vector<double> right(n, 0.0);
  for (size_t k = 1; k + 1 < n; ++k) {
    double known = k == 1 ? kOff * heights[0] : 0.0;
    known += k + 2 == n ? kOff * heights[n - 1] : 0.0;
    const double lower = k == 1 ? 0.0 : kOff;
    const double pivot = kDiagonal - lower * upper[k - 1];
    upper[k] = kOff / pivot;
    right[k] = (heights[k] - known - lower * right[k - 1]) / pivot;
  }
  controls[n - 2] = right[n - 2];
  for (size_t k = n - 2; k-- > 1;) {
    controls[k] = right[k] - upper[k] * controls[k + 1];
  }
  return controls;
}

// Value and first and second derivatives in U of the uniform cubic B-spline
// over control values c_0..c_{n-1} at U, clamped to [0, n - 3]; span j blends
// c_j..c_{j+3}.
template <typename T>
std::array<T, 3> uniformCubicBSpline(const std::vector<T>& control, double U) {
  const double U_end = static_cast<double>(control.size() - 3);
  U = std::clamp(U, 0.0, U_end);
  const int j = std::min(static_cast<int>(U), static_cast<int>(control.size()) - 4);
  const double u = U - j;
  const T& c0 = control[j];
  const T& c1 = control[j + 1];
  const T& c2 = control[j + 2];
  const T& c3 = control[j + 3];
  const double u2 = u * u;
  const double u3 = u2 * u;
  return {((1 - u) * (1 - u) * (1 - u) * c0 + (3 * u3 - 6 * u2 + 4) * c1 +
           (-3 * u3 + 3 * u2 + 3 * u + 1) * c2 + u3 * c3) /
              6.0,
          (-(1 - u) * (1 - u) * c0 + (3 * u2 - 4 * u) * c1 + (-3 * u2 + 2 * u + 1) * c2 + u2 * c3) /
              2.0,
          (1 - u) * c0 + (3 * u - 2) * c1 + (1 - 3 * u) * c2 + u * c3};
}

}  // namespace

RouteTrajectory::RouteTrajectory(
    const std::vector<Eigen::Vector2d>& waypoints,
    const std::function<double(const Eigen::Vector2d&)>& ground_height_m,
    const RouteDriveOptions& options)
    : options_(options) {
  if (waypoints.size() < 2 || !(options.control_spacing_m > 0.0) ||
      !(options.min_speed_m_s > 0.0) || options.max_speed_m_s < options.min_speed_m_s ||
      !(options.ramp_s > 0.0) || !(options.duration_s > 0.0)) {
    throw std::invalid_argument(fmt::format(
        "RouteTrajectory: need two waypoints ({} given), positive control spacing, ramp and "
        "duration, and 0 < min_speed <= max_speed",
        waypoints.size()));
  }
  if (!(options.initial_speed_m_s >= 0.0) || options.initial_speed_m_s > options.max_speed_m_s ||
      (options.initial_speed_m_s > 0.0 && options.initial_still_s != 0.0)) {
    throw std::invalid_argument(fmt::format(
        "RouteTrajectory: initial speed {} m/s must lie in [0, max_speed {}], and a drive that "
        "starts moving cannot stand still first (initial_still_s {} must be 0)",
        options.initial_speed_m_s, options.max_speed_m_s, options.initial_still_s));
  }
  control_ = resample(waypoints, options.control_spacing_m);
  if (control_.size() < 6) {
    throw std::invalid_argument(
        fmt::format("RouteTrajectory: route of {:.2f} m is shorter than the control spacing",
                    (waypoints.back() - waypoints.front()).norm()));
  }
  // Arclength table by Gauss-Legendre quadrature of |p'(U)| per step.
  const double U_end = static_cast<double>(control_.size() - 3);
  const int steps = static_cast<int>(std::ceil(U_end / kTableStep));
  arclength_.assign(1, 0.0);
  for (int i = 0; i < steps; ++i) {
    const double a = i * kTableStep;
    const double b = std::min(U_end, a + kTableStep);
    double length = 0.0;
    for (int k = 0; k < 5; ++k) {
      length +=
          kGaussWeights[k] * spline(0.5 * (a + b) + 0.5 * (b - a) * kGaussNodes[k]).first.norm();
    }
    arclength_.push_back(arclength_.back() + 0.5 * (b - a) * length);
  }
  // Unsigned curvature |p' x p''| / |p'|^3 at the same parameters.
  for (size_t i = 0; i < arclength_.size(); ++i) {
    const SplinePoint p = spline(std::min(U_end, static_cast<double>(i) * kTableStep));
    const double speed = p.first.norm();
    curvature_.push_back(speed > 1e-9
                             ? std::abs(p.first.x() * p.second.y() - p.first.y() * p.second.x()) /
                                   (speed * speed * speed)
                             : 0.0);
  }
  const int ground_spans =
      std::max(1, static_cast<int>(std::ceil(arclength_.back() / options_.control_spacing_m)));
  ground_spacing_m_ = arclength_.back() / ground_spans;
  std::vector<double> heights_m;
  for (int k = 0; k <= ground_spans; ++k) {
    heights_m.push_back(ground_height_m(spline(parameterAt(k * ground_spacing_m_)).position));
  }
  ground_control_m_ = interpolatingControls(heights_m);
  const size_t n = ground_control_m_.size();
  const double before_first =
      n > 1 ? 2.0 * ground_control_m_[0] - ground_control_m_[1] : ground_control_m_[0];
  const double after_last =
      n > 1 ? 2.0 * ground_control_m_[n - 1] - ground_control_m_[n - 2] : ground_control_m_[0];
  ground_control_m_.insert(ground_control_m_.begin(), before_first);
  ground_control_m_.push_back(after_last);
  planSpeed();
}

Eigen::Vector3d RouteTrajectory::groundHeight(double arclength_m) const {
  // x = s / spacing is the spline's parameter: d/ds = (1 / spacing) d/dx.
  const double spacing = ground_spacing_m_;
  const auto [height, first, second] =
      uniformCubicBSpline(ground_control_m_, arclength_m / spacing);
  return {height, first / spacing, second / (spacing * spacing)};
}

RouteTrajectory::SplinePoint RouteTrajectory::spline(double U) const {
  const auto [position, first, second] = uniformCubicBSpline(control_, U);
  return {position, first, second};
}

double RouteTrajectory::parameterAt(double arclength_m) const {
  const double s = std::clamp(arclength_m, 0.0, arclength_.back());
  const auto above = std::upper_bound(arclength_.begin(), arclength_.end(), s);
  const size_t i = std::clamp<size_t>(static_cast<size_t>(above - arclength_.begin()), 1,
                                      arclength_.size() - 1) -
                   1;
  const double U_end = static_cast<double>(control_.size() - 3);
  // Newton on L(U) = s from the table cell's start; L'(U) = |p'(U)|.
  double U = i * kTableStep;
  double length = arclength_[i];
  for (int iteration = 0; iteration < kNewtonIterations; ++iteration) {
    const double a = i * kTableStep;
    double segment = 0.0;
    for (int k = 0; k < 5; ++k) {
      segment +=
          kGaussWeights[k] * spline(0.5 * (a + U) + 0.5 * (U - a) * kGaussNodes[k]).first.norm();
    }
    length = arclength_[i] + 0.5 * (U - a) * segment;
    if (std::abs(length - s) < 1e-12) {
      break;
    }
    const double speed = spline(U).first.norm();
    if (!(speed > 1e-12)) {
      break;
    }
    U = std::clamp(U - (length - s) / speed, 0.0, U_end);
  }
  return U;
}

double RouteTrajectory::maxCurvature(double from_m, double to_m) const {
  const auto first = std::lower_bound(arclength_.begin(), arclength_.end(), from_m);
  const auto last = std::upper_bound(first, arclength_.end(), to_m);
  double max_curvature = 0.0;
  for (auto at = first; at != last; ++at) {
    max_curvature = std::max(max_curvature, curvature_[at - arclength_.begin()]);
  }
  return max_curvature;
}

void RouteTrajectory::planSpeed() {
  std::mt19937_64 random(options_.seed);
  const auto uniform = [&](double low, double high) {
    return std::uniform_real_distribution<double>(low, high)(random);
  };
  const double ramp = options_.ramp_s;
  double t = options_.initial_still_s;
  double v = options_.initial_speed_m_s;
  double covered = 0.0;  // distance at time t
  const double length = arclength_.back();
  while (t < options_.duration_s) {
    const bool stop = v > 0.0 && uniform(0.0, 1.0) < options_.stop_probability;
    const double cruise = stop ? uniform(options_.min_stop_s, options_.max_stop_s)
                               : uniform(options_.min_leg_s, options_.max_leg_s);
    double target = stop ? 0.0 : uniform(options_.min_speed_m_s, options_.max_speed_m_s);
    // The sharpest bend of the stretch this leg and the next ramp cover caps
    // the speed: k v^2 <= a_lat (never below the minimum cruise speed).
    const double stretch = 0.5 * (v + target) * ramp + target * (cruise + ramp);
    const double curvature = maxCurvature(covered, covered + stretch);
    if (!stop && curvature > 0.0) {
      target = std::clamp(std::sqrt(options_.max_lateral_acceleration_m_s2 / curvature),
                          options_.min_speed_m_s, target);
    }
    // Distance of this ramp and cruise, and of a final stop from `target`.
    const double leg = 0.5 * (v + target) * ramp + target * cruise;
    if (covered + leg + 0.5 * target * ramp > length) {
      // Not enough road left: cruise at v as far as possible, then stop.
      const double cruise_to_stop =
          std::max(0.0, (length - covered - 0.5 * v * ramp) / std::max(v, 1e-9));
      if (v > 0.0) {
        ramps_.push_back({t + cruise_to_stop, ramp, -v});
      }
      break;
    }
    ramps_.push_back({t, ramp, target - v});
    t += ramp + cruise;
    covered += leg;
    v = target;
  }
}

double RouteTrajectory::speed(double t) const {
  double v = options_.initial_speed_m_s;
  for (const Ramp& r : ramps_) {
    v += r.change_m_s * smoothstep(std::clamp((t - r.start_s) / r.duration_s, 0.0, 1.0));
  }
  return v;
}

double RouteTrajectory::acceleration(double t) const {
  double a = 0.0;
  for (const Ramp& r : ramps_) {
    const double u = (t - r.start_s) / r.duration_s;
    if (u > 0.0 && u < 1.0) {
      a += r.change_m_s * smoothstepRate(u) / r.duration_s;
    }
  }
  return a;
}

// s(t) = v0 t + sum over ramps of change * (d S(u) for u in the ramp, + (t - end) after it).
double RouteTrajectory::distance(double t) const {
  double s = options_.initial_speed_m_s * t;
  for (const Ramp& r : ramps_) {
    const double u = (t - r.start_s) / r.duration_s;
    if (u <= 0.0) {
      continue;
    }
    s += r.change_m_s * (u < 1.0 ? r.duration_s * smoothstepIntegral(u)
                                 : r.duration_s * 0.5 + (t - r.start_s - r.duration_s));
  }
  return s;
}

int64_t RouteTrajectory::endStamp_ns() const {
  return options_.start_stamp_ns + static_cast<int64_t>(std::llround(options_.duration_s * 1e9));
}

sim::TruthSample RouteTrajectory::at(int64_t stamp_ns) const {
  const int64_t clamped = std::clamp(stamp_ns, startStamp_ns(), endStamp_ns());
  const double t = static_cast<double>(clamped - options_.start_stamp_ns) * 1e-9;
  const double v = speed(t);
  const double dv = acceleration(t);
  const double s = distance(t);
  const SplinePoint p = spline(parameterAt(s));
  const double dp = p.first.norm();
  const Eigen::Vector2d tangent = p.first / dp;
  const Eigen::Vector2d normal(-tangent.y(), tangent.x());
  const double curvature =
      (p.first.x() * p.second.y() - p.first.y() * p.second.x()) / (dp * dp * dp);
  const double yaw = std::atan2(tangent.y(), tangent.x());
  const Eigen::Vector3d ground = groundHeight(s);
  const double grade = ground.y();
  const double pitch = std::atan(grade);
  const double pitch_rate = ground.z() * v / (1.0 + grade * grade);
  const double yaw_rate = curvature * v;
  sim::TruthSample sample;
  sample.stamp_ns = clamped;
  sample.p_world_body =
      Eigen::Vector3d(p.position.x(), p.position.y(), ground.x() + options_.body_height_m);
  sample.v_world_body << v * tangent, grade * v;
  sample.a_world_body << dv * tangent + curvature * v * v * normal, ground.z() * v * v + grade * dv;
  sample.q_world_body = Eigen::Quaterniond(Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()) *
                                           Eigen::AngleAxisd(-pitch, Eigen::Vector3d::UnitY()));
  sample.gyro_body_radps =
      Eigen::Vector3d(std::sin(pitch) * yaw_rate, -pitch_rate, std::cos(pitch) * yaw_rate);
  sample.specific_force_body_mps2 =
      sample.q_world_body.conjugate() *
      (sample.a_world_body + Eigen::Vector3d(0.0, 0.0, options_.gravity_m_s2));
  return sample;
}

}  // namespace lineloc
