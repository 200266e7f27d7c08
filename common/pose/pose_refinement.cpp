#include "common/pose/pose_refinement.h"

#include <fmt/format.h>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

#include "common/pose/pose_input_check.h"

namespace lineloc {

namespace {

using Vector6d = Eigen::Matrix<double, 6, 1>;
using Matrix26d = Eigen::Matrix<double, 2, 6>;

// Model points closer to the camera plane than this are "behind" it (metres).
constexpr double kMinDepthM = 1e-9;
// A camera farther than this from the world origin has diverged (metres).
constexpr double kMaxTranslationM = 1e3 * kMaxAbsCoordinate;
// Cost of a correspondence behind the camera: that of a 1000-sigma residual.
constexpr double kBehindCameraCost = 0.5 * 1e6;

Eigen::Matrix3d expSO3(const Eigen::Vector3d& rotation_vector) {
  const double angle = rotation_vector.norm();
  if (angle < 1e-300) {
    return Eigen::Matrix3d::Identity();
  }
  return Eigen::AngleAxisd(angle, rotation_vector / angle).toRotationMatrix();
}

// A measured point whitened by W with W^T W = Sigma^-1 (W = L^-1, Sigma = L L^T).
struct WhitenedPoint {
  Eigen::Vector3d p_world;
  Eigen::Vector2d pixel;
  Eigen::Matrix2d whitening;
};

// A measured line a + s (b - a) with unit normal n and the endpoints'
// variances along n.
struct MeasuredLine {
  Eigen::Vector3d endpoints_world[2];
  Eigen::Vector2d origin_px;
  Eigen::Vector2d direction_px;
  double inverse_squared_length;
  Eigen::Vector2d normal;
  double start_variance;
  double end_variance;
};

struct PreparedProblem {
  PinholeCamera camera;
  std::vector<WhitenedPoint> points;
  std::vector<MeasuredLine> lines;
};

PreparedProblem prepare(const PoseProblem& problem) {
  PreparedProblem prepared{problem.camera, {}, {}};
  prepared.points.reserve(problem.points.size());
  for (const auto& point : problem.points) {
    const Eigen::Matrix2d L = point.covariance.llt().matrixL();
    prepared.points.push_back({point.p_world, point.pixel, L.inverse()});
  }
  prepared.lines.reserve(problem.lines.size());
  for (const auto& line : problem.lines) {
    const Eigen::Vector2d direction = line.end_pixel - line.start_pixel;
    const Eigen::Vector2d normal = Eigen::Vector2d(-direction.y(), direction.x()).normalized();
    prepared.lines.push_back({{line.start_world, line.end_world},
                              line.start_pixel,
                              direction,
                              1.0 / direction.squaredNorm(),
                              normal,
                              normal.dot(line.start_covariance * normal),
                              normal.dot(line.end_covariance * normal)});
  }
  return prepared;
}

// Projection of p_c and its Jacobian with respect to [dt; dtheta].
struct Projection {
  Eigen::Vector2d pixel;
  Matrix26d jacobian;
};

bool project(const PinholeCamera& camera, const Eigen::Isometry3d& T_camera_world,
             const Eigen::Vector3d& p_world, Projection* projection) {
  const Eigen::Vector3d p_c = T_camera_world * p_world;
  if (!(p_c.z() > kMinDepthM)) {
    return false;
  }
  const double inverse_z = 1.0 / p_c.z();
  const double x = p_c.x() * inverse_z;
  const double y = p_c.y() * inverse_z;
  projection->pixel = {camera.fx * x + camera.skew * y + camera.cx, camera.fy * y + camera.cy};
  Eigen::Matrix<double, 2, 3> d_pixel_d_pc;
  d_pixel_d_pc << camera.fx * inverse_z, camera.skew * inverse_z,
      -(camera.fx * x + camera.skew * y) * inverse_z, 0.0, camera.fy * inverse_z,
      -camera.fy * y * inverse_z;
  projection->jacobian.leftCols<3>() = d_pixel_d_pc;
  projection->jacobian.rightCols<3>() = -d_pixel_d_pc * skew(p_c);
  return true;
}

// One correspondence's normalized residual (2-vector), its Jacobian and its
// residual in pixels.
struct Term {
  Eigen::Vector2d normalized;
  Matrix26d jacobian;
  double residual_px;
};

bool pointTerm(const PinholeCamera& camera, const Eigen::Isometry3d& T_camera_world,
               const WhitenedPoint& point, Term* term) {
  Projection projection;
  if (!project(camera, T_camera_world, point.p_world, &projection)) {
    return false;
  }
  const Eigen::Vector2d error_px = projection.pixel - point.pixel;
  term->normalized = point.whitening * error_px;
  term->jacobian = point.whitening * projection.jacobian;
  term->residual_px = error_px.norm();
  return true;
}

bool lineTerm(const PinholeCamera& camera, const Eigen::Isometry3d& T_camera_world,
              const MeasuredLine& line, Term* term) {
  double squared_px = 0.0;
  for (int k = 0; k < 2; ++k) {
    Projection projection;
    if (!project(camera, T_camera_world, line.endpoints_world[k], &projection)) {
      return false;
    }
    const Eigen::Vector2d offset = projection.pixel - line.origin_px;
    const double distance_px = line.normal.dot(offset);
    const double s = offset.dot(line.direction_px) * line.inverse_squared_length;
    const double sigma =
        std::sqrt((1.0 - s) * (1.0 - s) * line.start_variance + s * s * line.end_variance);
    term->normalized(k) = distance_px / sigma;
    term->jacobian.row(k) = line.normal.transpose() * projection.jacobian / sigma;
    squared_px += distance_px * distance_px;
  }
  term->residual_px = std::sqrt(squared_px);
  return true;
}

// rho(s) and rho'(s) of the robust loss at s = |r|^2.
struct LossValue {
  double rho;
  double derivative;
};

LossValue evaluateLoss(RobustLoss loss, double c, double s) {
  switch (loss) {
    case RobustLoss::kHuber: {
      if (s <= c * c) {
        return {s, 1.0};
      }
      const double norm = std::sqrt(s);
      return {2.0 * c * norm - c * c, c / norm};
    }
    case RobustLoss::kCauchy:
      return {c * c * std::log1p(s / (c * c)), 1.0 / (1.0 + s / (c * c))};
    case RobustLoss::kNone:
      break;
  }
  return {s, 1.0};
}

// Calls visit(term, is_line, index) for every correspondence in front of the
// camera; returns how many are not.
template <typename Visitor>
size_t visitTerms(const PreparedProblem& problem, const Eigen::Isometry3d& T_camera_world,
                  Visitor&& visit) {
  size_t behind = 0;
  Term term;
  for (size_t i = 0; i < problem.points.size(); ++i) {
    if (pointTerm(problem.camera, T_camera_world, problem.points[i], &term)) {
      visit(term, false, i);
    } else {
      ++behind;
    }
  }
  for (size_t i = 0; i < problem.lines.size(); ++i) {
    if (lineTerm(problem.camera, T_camera_world, problem.lines[i], &term)) {
      visit(term, true, i);
    } else {
      ++behind;
    }
  }
  return behind;
}

// The Gauss–Newton system J^T W J, J^T W r of the sqrt(rho')-scaled residuals.
// A correspondence behind the camera adds the constant kBehindCameraCost and
// no gradient, so that a start seeing a few features behind the camera (a
// noisy linear start) can still bring them in front.
struct Linearization {
  size_t behind = 0;
  double cost = 0.0;
  Matrix6d information = Matrix6d::Zero();
  Vector6d gradient = Vector6d::Zero();
};

Linearization linearize(const PreparedProblem& problem, const Eigen::Isometry3d& T_camera_world,
                        const RefinementOptions& options) {
  Linearization result;
  result.behind = visitTerms(problem, T_camera_world, [&](const Term& term, bool, size_t) {
    const LossValue loss =
        evaluateLoss(options.loss, options.loss_scale, term.normalized.squaredNorm());
    result.cost += 0.5 * loss.rho;
    result.information.noalias() += loss.derivative * term.jacobian.transpose() * term.jacobian;
    result.gradient.noalias() += loss.derivative * term.jacobian.transpose() * term.normalized;
  });
  result.cost += kBehindCameraCost * static_cast<double>(result.behind);
  return result;
}

Eigen::Isometry3d applyStep(const Eigen::Isometry3d& T_camera_world, const Vector6d& step) {
  Eigen::Isometry3d updated = Eigen::Isometry3d::Identity();
  const Eigen::Matrix3d rotation = expSO3(step.tail<3>());
  updated.linear() = rotation * T_camera_world.linear();
  updated.translation() = rotation * T_camera_world.translation() + step.head<3>();
  return updated;
}

bool isSmallStep(const Vector6d& step, const Eigen::Isometry3d& T_camera_world, double tolerance) {
  const double translation_scale = T_camera_world.translation().norm() + tolerance;
  return step.head<3>().norm() <= tolerance * translation_scale &&
         step.tail<3>().norm() <= tolerance;
}

bool isDegenerate(const Matrix6d& information, double threshold) {
  const Vector6d scale = information.diagonal().cwiseMax(1e-300).cwiseSqrt().cwiseInverse();
  const Matrix6d scaled = scale.asDiagonal() * information * scale.asDiagonal();
  const Vector6d eigenvalues =
      Eigen::SelfAdjointEigenSolver<Matrix6d>(scaled, Eigen::EigenvaluesOnly).eigenvalues();
  return !(eigenvalues(0) > threshold * eigenvalues(5));
}

// Covariance of T_world_camera in the pose.h convention from the covariance of
// the left perturbation [dt; dtheta] of T_camera_world: T_world_camera' =
// T_world_camera (Exp(dtheta), dt)^-1 gives dp = -R_wc dt, dphi = -R_wc dtheta.
Matrix6d worldCovariance(const Matrix6d& camera_covariance, const Eigen::Matrix3d& R_world_camera) {
  Matrix6d rotate = Matrix6d::Zero();
  rotate.topLeftCorner<3, 3>() = R_world_camera;
  rotate.bottomRightCorner<3, 3>() = R_world_camera;
  const Matrix6d covariance = rotate * camera_covariance * rotate.transpose();
  return 0.5 * (covariance + covariance.transpose());
}

// The RMS of the correspondences' normalized residuals for least squares;
// their median with a robust loss, which expects outliers.
double residualSpread(std::vector<double>& normalized, RobustLoss loss) {
  if (loss == RobustLoss::kNone) {
    double squared = 0.0;
    for (const double r : normalized)
      squared += r * r;
    return std::sqrt(squared / static_cast<double>(normalized.size()));
  }
  const auto median = normalized.begin() + static_cast<std::ptrdiff_t>(normalized.size() / 2);
  std::nth_element(normalized.begin(), median, normalized.end());
  return *median;
}

// Residuals, RMS, covariance and the final status checks at the solution.
PoseEstimate summarize(const PreparedProblem& problem, const Eigen::Isometry3d& T_camera_world,
                       const Linearization& linearization, const RefinementOptions& options,
                       PoseStatus status, int iterations) {
  if (linearization.behind > 0) {
    return poseFailure(PoseStatus::kBehindCamera,
                       fmt::format("{} model points or segments are not in front of the camera",
                                   linearization.behind));
  }
  PoseEstimate estimate;
  estimate.iterations = iterations;
  estimate.cost = linearization.cost;
  estimate.point_residuals.resize(problem.points.size());
  estimate.line_residuals.resize(problem.lines.size());
  double squared_px = 0.0;
  std::vector<double> normalized;
  visitTerms(problem, T_camera_world, [&](const Term& term, bool is_line, size_t i) {
    const double s = term.normalized.squaredNorm();
    auto& residual = is_line ? estimate.line_residuals[i] : estimate.point_residuals[i];
    residual = {term.residual_px, std::sqrt(s),
                evaluateLoss(options.loss, options.loss_scale, s).derivative};
    squared_px += term.residual_px * term.residual_px;
    normalized.push_back(residual.normalized_residual);
  });
  estimate.rms_residual_px = std::sqrt(squared_px / (2.0 * static_cast<double>(normalized.size())));
  estimate.T_world_camera.pose = T_camera_world.inverse();
  estimate.status = status;
  if (status == PoseStatus::kIterationLimit) {
    estimate.message = fmt::format("no convergence in {} iterations", iterations);
  }
  if (isDegenerate(linearization.information, options.degeneracy_threshold)) {
    estimate.status = PoseStatus::kDegenerate;
    estimate.message = "the correspondences do not determine all six pose parameters";
    return estimate;
  }
  estimate.T_world_camera.covariance =
      worldCovariance(linearization.information.inverse(), estimate.T_world_camera.pose.linear());
  const double spread = residualSpread(normalized, options.loss);
  if (status == PoseStatus::kConverged && spread > options.max_normalized_residual) {
    estimate.status = PoseStatus::kInconsistent;
    estimate.message = fmt::format("normalized residuals ({} {}) exceed {}",
                                   options.loss == RobustLoss::kNone ? "RMS" : "median", spread,
                                   options.max_normalized_residual);
  }
  if (!isFinitePose(estimate.T_world_camera)) {
    estimate.status = PoseStatus::kDiverged;
    estimate.message = "the refined pose or its covariance is not finite";
  }
  return estimate;
}

}  // namespace

PoseEstimate refineCheckedPose(const PoseProblem& problem,
                               const Eigen::Isometry3d& T_world_camera_start,
                               const RefinementOptions& options) {
  PoseWithCovariance start{T_world_camera_start, Matrix6d::Zero()};
  if (!isFinitePose(start, 1e-6)) {
    return poseFailure(PoseStatus::kInvalidInput, "start pose: not finite or not a rotation");
  }
  const PreparedProblem prepared = prepare(problem);
  Eigen::Isometry3d T_camera_world = T_world_camera_start.inverse();
  Linearization current = linearize(prepared, T_camera_world, options);
  if (current.behind == problem.points.size() + problem.lines.size()) {
    return poseFailure(PoseStatus::kBehindCamera,
                       "start pose: no model point or endpoint is in front of the camera");
  }
  double damping = options.initial_damping;
  for (int iteration = 0; iteration < options.max_iterations; ++iteration) {
    if (!std::isfinite(current.cost) || !current.information.allFinite()) {
      return poseFailure(PoseStatus::kDiverged, "refinement: the cost became non-finite");
    }
    if (current.gradient.cwiseAbs().maxCoeff() <= options.gradient_tolerance) {
      return summarize(prepared, T_camera_world, current, options, PoseStatus::kConverged,
                       iteration);
    }
    Matrix6d damped = current.information;
    damped.diagonal() += damping * current.information.diagonal().cwiseMax(1e-12);
    const Vector6d step = damped.ldlt().solve(-current.gradient);
    if (!step.allFinite()) {
      return poseFailure(PoseStatus::kDiverged, "refinement: the step is not finite");
    }
    if (isSmallStep(step, T_camera_world, options.parameter_tolerance) ||
        step.dot(current.information * step) < options.step_information_tolerance) {
      return summarize(prepared, T_camera_world, current, options, PoseStatus::kConverged,
                       iteration);
    }
    const Eigen::Isometry3d candidate = applyStep(T_camera_world, step);
    Linearization trial = linearize(prepared, candidate, options);
    if (!(trial.cost < current.cost)) {
      damping *= 10.0;
      if (damping > options.max_damping) {
        return summarize(prepared, T_camera_world, current, options, PoseStatus::kConverged,
                         iteration);
      }
      continue;
    }
    const double relative_decrease = (current.cost - trial.cost) / current.cost;
    T_camera_world = candidate;
    current = std::move(trial);
    damping = std::max(damping * 0.1, 1e-12);
    if (T_camera_world.translation().norm() > kMaxTranslationM) {
      return poseFailure(PoseStatus::kDiverged, "refinement: the camera left the model's range");
    }
    if (relative_decrease < options.function_tolerance) {
      return summarize(prepared, T_camera_world, current, options, PoseStatus::kConverged,
                       iteration + 1);
    }
  }
  return summarize(prepared, T_camera_world, current, options, PoseStatus::kIterationLimit,
                   options.max_iterations);
}

Matrix6d leaveGroupOutCovariance(const PoseProblem& problem,
                                 const Eigen::Isometry3d& T_world_camera,
                                 const std::vector<int>& line_groups,
                                 const RefinementOptions& options) {
  struct GroupSystem {
    bool used = false;
    Matrix6d information = Matrix6d::Zero();
    Vector6d gradient = Vector6d::Zero();
  };
  const size_t lines = problem.lines.size();
  const bool valid = line_groups.size() == lines &&
                     std::all_of(line_groups.begin(), line_groups.end(), [lines](int group) {
                       return group >= 0 && static_cast<size_t>(group) < lines;
                     });
  if (!valid) {
    throw std::invalid_argument("leaveGroupOutCovariance: one group in [0, lines) per line");
  }
  // Line groups first, then one group per point.
  std::vector<GroupSystem> groups(lines + problem.points.size());
  visitTerms(
      prepare(problem), T_world_camera.inverse(), [&](const Term& term, bool is_line, size_t i) {
        const double weight =
            evaluateLoss(options.loss, options.loss_scale, term.normalized.squaredNorm())
                .derivative;
        GroupSystem& group = groups[is_line ? static_cast<size_t>(line_groups[i]) : lines + i];
        group.used = true;
        group.information.noalias() += weight * term.jacobian.transpose() * term.jacobian;
        group.gradient.noalias() += weight * term.jacobian.transpose() * term.normalized;
      });
  groups.erase(std::remove_if(groups.begin(), groups.end(),
                              [](const GroupSystem& group) { return !group.used; }),
               groups.end());
  Matrix6d information = Matrix6d::Zero();
  for (const GroupSystem& group : groups) {
    information += group.information;
  }
  const Matrix6d undetermined = Matrix6d::Identity() * std::numeric_limits<double>::infinity();
  if (groups.size() < 2) {
    return undetermined;
  }
  std::vector<Vector6d> shifts;
  shifts.reserve(groups.size());
  for (const GroupSystem& group : groups) {
    const Matrix6d without = information - group.information;
    if (isDegenerate(without, options.degeneracy_threshold)) {
      return undetermined;
    }
    shifts.push_back(without.ldlt().solve(group.gradient));
  }
  const double count = static_cast<double>(shifts.size());
  return worldCovariance((count - 1.0) / count * scatterAboutMean(shifts), T_world_camera.linear());
}

PoseEstimate refinePose(const PoseProblem& problem, const Eigen::Isometry3d& T_world_camera_start,
                        const RefinementOptions& options) {
  if (auto invalid = checkPoseInput(problem)) {
    return poseFailure(invalid->status, invalid->message);
  }
  if (auto degenerate = checkPoseGeometry(problem)) {
    return poseFailure(degenerate->status, degenerate->message);
  }
  return refineCheckedPose(problem, T_world_camera_start, options);
}

}  // namespace lineloc
