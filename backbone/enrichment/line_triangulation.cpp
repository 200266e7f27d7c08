#include "backbone/enrichment/line_triangulation.h"

#include <fmt/format.h>

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>
#include <utility>

namespace lineloc {
namespace {

constexpr double kStep = 1e-6;

// A line about the local origin: unit direction u and moment m' = p x u.
struct LocalLine {
  Eigen::Vector3d direction;
  Eigen::Vector3d moment;
  // Its point nearest the origin: u x m'.
  Eigen::Vector3d closestPoint() const { return direction.cross(moment); }
};

// The orthonormal representation (see the header): U and phi, the line
// (cos(phi) u1, sin(phi) u2), so that its distance from the origin is tan(phi).
struct FreeLine {
  static constexpr int kDof = 4;
  Eigen::Matrix3d U;
  double phi = 0.0;

  static std::optional<FreeLine> from(const LocalLine& line) {
    const double distance = line.moment.norm();
    if (!(distance > 1e-9)) {
      return std::nullopt;
    }
    FreeLine free;
    free.U.col(0) = line.direction.normalized();
    free.U.col(1) = line.moment / distance;
    free.U.col(2) = free.U.col(0).cross(free.U.col(1));
    free.phi = std::atan(distance);
    return free;
  }
  FreeLine plus(const Eigen::Matrix<double, kDof, 1>& delta) const {
    FreeLine moved = *this;
    const Eigen::Vector3d theta = delta.head<3>();
    const double angle = theta.norm();
    if (angle > 0.0) {
      moved.U = U * Eigen::AngleAxisd(angle, theta / angle).toRotationMatrix();
    }
    moved.phi = phi + delta(3);
    return moved;
  }
  LocalLine line() const { return {U.col(0), std::tan(phi) * U.col(1)}; }
};

// A line in a plane: the angle of its direction in the plane's basis and its
// offset from the plane's point nearest the origin, across the direction.
struct PlaneLine {
  static constexpr int kDof = 2;
  Eigen::Vector3d normal;
  Eigen::Vector3d basis_x;
  Eigen::Vector3d basis_y;
  Eigen::Vector3d origin;  // the plane's point nearest the local origin
  double angle = 0.0;
  double offset = 0.0;

  // `line` (lying in the plane) in its parameters.
  static PlaneLine from(const LocalLine& line, const Plane& local_plane) {
    PlaneLine in_plane;
    in_plane.normal = local_plane.normal.normalized();
    in_plane.basis_x = in_plane.normal.unitOrthogonal();
    in_plane.basis_y = in_plane.normal.cross(in_plane.basis_x);
    in_plane.origin = local_plane.offset * in_plane.normal;
    in_plane.angle =
        std::atan2(line.direction.dot(in_plane.basis_y), line.direction.dot(in_plane.basis_x));
    in_plane.offset = (line.closestPoint() - in_plane.origin).dot(in_plane.across());
    return in_plane;
  }
  Eigen::Vector3d direction() const {
    return std::cos(angle) * basis_x + std::sin(angle) * basis_y;
  }
  Eigen::Vector3d across() const { return normal.cross(direction()); }
  PlaneLine plus(const Eigen::Matrix<double, kDof, 1>& delta) const {
    PlaneLine moved = *this;
    moved.angle += delta(0);
    moved.offset += delta(1);
    return moved;
  }
  LocalLine line() const {
    const Eigen::Vector3d u = direction();
    const Eigen::Vector3d point = origin + offset * across();
    return {u, point.cross(u)};
  }
};

// A view about the local origin.
struct LocalView {
  Eigen::Matrix3d R;       // world (and local) from camera
  Eigen::Vector3d centre;  // local frame
  Eigen::Matrix3d K;
  Eigen::Matrix3d K_inverse;
  Matrix6d pose_covariance;
  std::array<Eigen::Vector2d, 2> endpoints;
  std::array<Eigen::Matrix2d, 2> endpoint_covariances;
};

LocalView localView(const LineObservation& observation, const Eigen::Vector3d& origin) {
  LocalView view;
  view.R = observation.T_world_camera.pose.linear();
  view.centre = observation.T_world_camera.pose.translation() - origin;
  view.K = observation.camera.K();
  view.K_inverse = view.K.inverse();
  view.pose_covariance = observation.T_world_camera.covariance;
  view.endpoints = {observation.segment.start.cast<double>(),
                    observation.segment.end.cast<double>()};
  view.endpoint_covariances = {observation.segment.start_covariance.cast<double>(),
                               observation.segment.end_covariance.cast<double>()};
  return view;
}

// The image of `line` in the view: l = K^-T R^T (m - c x d).
Eigen::Vector3d imageLine(const LocalView& view, const LocalLine& line) {
  return view.K_inverse.transpose() *
         (view.R.transpose() * (line.moment - view.centre.cross(line.direction)));
}

// The signed pixel distances of the view's endpoints from the image of `line`.
Eigen::Vector2d endpointResiduals(const LocalView& view, const LocalLine& line) {
  const Eigen::Vector3d l = imageLine(view, line);
  const double scale = l.head<2>().norm();
  Eigen::Vector2d residuals;
  for (int j = 0; j < 2; ++j) {
    residuals(j) = l.dot(view.endpoints[j].homogeneous()) / scale;
  }
  return residuals;
}

// The variance of each residual: its endpoint's across the image line, and
// the view's pose's, e = [dp; dtheta] with t' = t + dp, R' = Exp(dtheta) R.
Eigen::Vector2d residualVariances(const LocalView& view, const LocalLine& line) {
  const Eigen::Vector2d normal = imageLine(view, line).head<2>().normalized();
  const Eigen::Vector2d residuals = endpointResiduals(view, line);
  Eigen::Matrix<double, 2, 6> d_residual_d_pose;
  for (int k = 0; k < 6; ++k) {
    LocalView moved = view;
    if (k < 3) {
      moved.centre(k) += kStep;
    } else {
      moved.R = Eigen::AngleAxisd(kStep, Eigen::Vector3d::Unit(k - 3)).toRotationMatrix() * view.R;
    }
    d_residual_d_pose.col(k) = (endpointResiduals(moved, line) - residuals) / kStep;
  }
  const Eigen::Matrix2d pose_part =
      d_residual_d_pose * view.pose_covariance * d_residual_d_pose.transpose();
  Eigen::Vector2d variances;
  for (int j = 0; j < 2; ++j) {
    variances(j) = normal.dot(view.endpoint_covariances[j] * normal) + pose_part(j, j);
  }
  return variances;
}

// The plane through a view's camera and its segment, [n; -n . c].
Eigen::Vector4d viewPlane(const LocalView& view) {
  const Eigen::Vector3d l = view.endpoints[0].homogeneous().cross(view.endpoints[1].homogeneous());
  const Eigen::Vector3d normal = (view.R * (view.K.transpose() * l)).normalized();
  Eigen::Vector4d plane;
  plane << normal, -normal.dot(view.centre);
  return plane;
}

// The line where `a` and `b`, [n; -offset] each, meet.
LocalLine intersection(const Eigen::Vector4d& a, const Eigen::Vector4d& b) {
  const Eigen::Vector3d u = a.head<3>().cross(b.head<3>()).normalized();
  Eigen::Matrix2d gram;
  gram << a.head<3>().squaredNorm(), a.head<3>().dot(b.head<3>()), a.head<3>().dot(b.head<3>()),
      b.head<3>().squaredNorm();
  const Eigen::Vector2d weights = gram.ldlt().solve(Eigen::Vector2d(-a(3), -b(3)));
  const Eigen::Vector3d point = weights(0) * a.head<3>() + weights(1) * b.head<3>();
  return {u, point.cross(u)};
}

// The linear triangulation: the line spanned by the two points nearest the
// null space of the views' planes.
LocalLine linearLine(const std::vector<Eigen::Vector4d>& planes) {
  Eigen::MatrixXd A(static_cast<Eigen::Index>(planes.size()), 4);
  for (size_t i = 0; i < planes.size(); ++i) {
    A.row(static_cast<Eigen::Index>(i)) = planes[i].transpose();
  }
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(A, Eigen::ComputeFullV);
  const Eigen::Vector4d P = svd.matrixV().col(2);
  const Eigen::Vector4d Q = svd.matrixV().col(3);
  const Eigen::Vector3d d = P(3) * Q.head<3>() - Q(3) * P.head<3>();
  const Eigen::Vector3d m = P.head<3>().cross(Q.head<3>());
  const double length = d.norm();
  return {d / length, m / length};
}

template <typename State>
using StateVector = Eigen::Matrix<double, State::kDof, 1>;

// The views' residuals divided by their standard deviations.
template <typename State>
Eigen::VectorXd whitenedResiduals(const std::vector<LocalView>& views, const State& state,
                                  const std::vector<Eigen::Vector2d>& variances) {
  Eigen::VectorXd residuals(2 * static_cast<Eigen::Index>(views.size()));
  const LocalLine line = state.line();
  for (size_t i = 0; i < views.size(); ++i) {
    const Eigen::Vector2d r = endpointResiduals(views[i], line);
    residuals.segment<2>(2 * static_cast<Eigen::Index>(i)) =
        r.cwiseQuotient(variances[i].cwiseSqrt());
  }
  return residuals;
}

template <typename State>
Eigen::MatrixXd jacobian(const std::vector<LocalView>& views, const State& state,
                         const std::vector<Eigen::Vector2d>& variances) {
  Eigen::MatrixXd J(2 * static_cast<Eigen::Index>(views.size()), State::kDof);
  for (int k = 0; k < State::kDof; ++k) {
    const StateVector<State> step = StateVector<State>::Unit(k) * kStep;
    J.col(k) = (whitenedResiduals(views, state.plus(step), variances) -
                whitenedResiduals(views, state.plus(-step), variances)) /
               (2.0 * kStep);
  }
  return J;
}

std::vector<Eigen::Vector2d> variancesAt(const std::vector<LocalView>& views,
                                         const LocalLine& line) {
  std::vector<Eigen::Vector2d> variances;
  for (const LocalView& view : views) {
    variances.push_back(residualVariances(view, line));
  }
  return variances;
}

// The refined state, its covariance and the residuals' variances there.
template <typename State>
struct Refined {
  State state;
  Eigen::MatrixXd covariance;
  std::vector<Eigen::Vector2d> variances;
};

// Gauss-Newton from `state`, a step halved while it raises the cost.
template <typename State>
Refined<State> refine(const std::vector<LocalView>& views, State state, int max_iterations) {
  for (int iteration = 0; iteration < max_iterations; ++iteration) {
    const std::vector<Eigen::Vector2d> variances = variancesAt(views, state.line());
    const Eigen::VectorXd r = whitenedResiduals(views, state, variances);
    const Eigen::MatrixXd J = jacobian(views, state, variances);
    const StateVector<State> step = (J.transpose() * J).ldlt().solve(-J.transpose() * r);
    double scale = 1.0;
    bool moved = false;
    for (int halving = 0; halving < 10 && !moved; ++halving, scale /= 2.0) {
      const State candidate = state.plus(scale * step);
      if (whitenedResiduals(views, candidate, variances).squaredNorm() <= r.squaredNorm()) {
        state = candidate;
        moved = true;
      }
    }
    if (!moved || step.norm() < 1e-12) {
      break;
    }
  }
  const std::vector<Eigen::Vector2d> variances = variancesAt(views, state.line());
  const Eigen::MatrixXd J = jacobian(views, state, variances);
  return {state, (J.transpose() * J).inverse(), variances};
}

// The position along `line` (from its closest point to the origin) where the
// ray from `centre` along `ray` passes nearest; nullopt for a ray parallel to it.
std::optional<double> positionAlong(const LocalLine& line, const Eigen::Vector3d& centre,
                                    const Eigen::Vector3d& ray) {
  const Eigen::Vector3d u = line.direction;
  const Eigen::Vector3d w0 = line.closestPoint() - centre;
  const double b = u.dot(ray);
  const double c = ray.dot(ray);
  const double denominator = c - b * b;
  if (!(denominator > 1e-12 * c)) {
    return std::nullopt;
  }
  return (b * ray.dot(w0) - c * u.dot(w0)) / denominator;
}

// The positions along `line` that at least two views' segments reach.
std::optional<std::pair<double, double>> extentAlong(const std::vector<LocalView>& views,
                                                     const LocalLine& line) {
  std::vector<std::pair<double, int>> events;  // +1 where a view's reach starts, -1 ends
  for (const LocalView& view : views) {
    std::array<double, 2> s{};
    for (int j = 0; j < 2; ++j) {
      const std::optional<double> at = positionAlong(
          line, view.centre, view.R * (view.K_inverse * view.endpoints[j].homogeneous()));
      if (!at) {
        return std::nullopt;
      }
      s[static_cast<size_t>(j)] = *at;
    }
    events.push_back({std::min(s[0], s[1]), +1});
    events.push_back({std::max(s[0], s[1]), -1});
  }
  std::ranges::sort(events, [](const auto& a, const auto& b) {
    return a.first < b.first || (a.first == b.first && a.second > b.second);
  });
  std::optional<double> first;
  std::optional<double> last;
  int reaching = 0;
  for (const auto& [position, change] : events) {
    if (change < 0 && reaching >= 2) {
      last = position;
    }
    reaching += change;
    if (change > 0 && reaching >= 2 && !first) {
      first = position;
    }
  }
  if (!first || !last || !(*last > *first)) {
    return std::nullopt;
  }
  return std::pair(*first, *last);
}

// Covariance of the point at `position` along the line, from the state's,
// across the line: (I - u u^T) J Sigma J^T (I - u u^T).
template <typename State>
Eigen::Matrix3d pointCovariance(const State& state, const Eigen::MatrixXd& covariance,
                                double position) {
  const auto pointAt = [&](const State& at) {
    const LocalLine line = at.line();
    return Eigen::Vector3d(line.closestPoint() + position * line.direction);
  };
  Eigen::Matrix<double, 3, State::kDof> J;
  for (int k = 0; k < State::kDof; ++k) {
    const StateVector<State> step = StateVector<State>::Unit(k) * kStep;
    J.col(k) = (pointAt(state.plus(step)) - pointAt(state.plus(-step))) / (2.0 * kStep);
  }
  const Eigen::Vector3d u = state.line().direction;
  const Eigen::Matrix3d across = Eigen::Matrix3d::Identity() - u * u.transpose();
  return across * J * covariance * J.transpose() * across;
}

template <typename State>
LineTriangulation finish(const std::vector<LocalView>& views, const State& start,
                         const Eigen::Vector3d& origin, const LineTriangulationOptions& options) {
  const auto [state, covariance, variances] = refine(views, start, options.max_iterations);
  const LocalLine line = state.line();
  TriangulatedLine result;
  for (size_t i = 0; i < views.size(); ++i) {
    const Eigen::Vector2d r = endpointResiduals(views[i], line);
    const double chi2 = r.cwiseAbs2().cwiseQuotient(variances[i]).sum();
    result.view_chi2.push_back(chi2);
    if (!(chi2 <= options.max_view_chi2)) {
      return {std::nullopt, fmt::format("view {} sees it with chi^2 {:.1f}, beyond {:.1f}", i, chi2,
                                        options.max_view_chi2)};
    }
  }
  const std::optional<std::pair<double, double>> extent = extentAlong(views, line);
  if (!extent) {
    return {std::nullopt, "no two views' segments overlap along it"};
  }
  const Eigen::Vector3d closest = line.closestPoint();
  result.start_world = origin + closest + extent->first * line.direction;
  result.end_world = origin + closest + extent->second * line.direction;
  result.direction = line.direction;
  result.moment = (origin + closest).cross(line.direction);
  result.start_covariance = pointCovariance(state, covariance, extent->first);
  result.end_covariance = pointCovariance(state, covariance, extent->second);
  result.dof = State::kDof;
  result.parameter_covariance.topLeftCorner<State::kDof, State::kDof>() = covariance;
  return {result, ""};
}

}  // namespace

LineTriangulation triangulateLine(const std::vector<LineObservation>& observations,
                                  const LineTriangulationOptions& options,
                                  const std::optional<Plane>& plane) {
  if (static_cast<int>(observations.size()) < options.min_views) {
    return {std::nullopt,
            fmt::format("{} views, {} needed", observations.size(), options.min_views)};
  }
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();
  for (const LineObservation& observation : observations) {
    origin += observation.T_world_camera.pose.translation();
  }
  origin /= static_cast<double>(observations.size());
  std::vector<LocalView> views;
  std::vector<Eigen::Vector4d> planes;
  double baseline_m = 0.0;
  double plane_angle_rad = 0.0;
  for (const LineObservation& observation : observations) {
    views.push_back(localView(observation, origin));
    const Eigen::Vector2d along = views.back().endpoints[1] - views.back().endpoints[0];
    if (!(along.norm() > 1e-3)) {
      return {std::nullopt, fmt::format("view {}: its segment has no length, or is not finite",
                                        views.size() - 1)};
    }
    planes.push_back(viewPlane(views.back()));
    for (size_t i = 0; i + 1 < views.size(); ++i) {
      baseline_m = std::max(baseline_m, (views[i].centre - views.back().centre).norm());
      const double cosine = std::abs(planes[i].head<3>().dot(planes.back().head<3>()));
      plane_angle_rad = std::max(plane_angle_rad, std::acos(std::min(cosine, 1.0)));
    }
  }
  if (baseline_m < options.min_baseline_m) {
    return {std::nullopt, fmt::format("the cameras lie within {:.2f} m, {:.2f} m needed",
                                      baseline_m, options.min_baseline_m)};
  }
  if (plane) {
    // In a plane, each view's plane meets it in the line: the angle between
    // them is what conditions it.
    plane_angle_rad = 0.0;
    for (const Eigen::Vector4d& view_plane : planes) {
      const double cosine = std::abs(view_plane.head<3>().dot(plane->normal.normalized()));
      plane_angle_rad = std::max(plane_angle_rad, std::acos(std::min(cosine, 1.0)));
    }
  }
  if (plane_angle_rad < options.min_plane_angle_rad) {
    return {std::nullopt,
            fmt::format("the views' planes meet {} at {:.2f} deg at most, {:.2f} deg needed",
                        plane ? "the given plane" : "each other", plane_angle_rad * 180.0 / M_PI,
                        options.min_plane_angle_rad * 180.0 / M_PI)};
  }
  if (plane) {
    const Plane local{plane->normal.normalized(), plane->offset / plane->normal.norm() -
                                                      plane->normal.normalized().dot(origin)};
    // The start: where the view plane meeting the given one most steeply meets it.
    Eigen::Vector4d given;
    given << local.normal, -local.offset;
    const auto steepest = std::ranges::min_element(planes, {}, [&](const Eigen::Vector4d& view) {
      return std::abs(view.head<3>().dot(local.normal));
    });
    return finish(views, PlaneLine::from(intersection(given, *steepest), local), origin, options);
  }
  const std::optional<FreeLine> start = FreeLine::from(linearLine(planes));
  if (!start) {
    return {std::nullopt, "the line passes through the cameras' mean centre"};
  }
  return finish(views, *start, origin, options);
}

}  // namespace lineloc
