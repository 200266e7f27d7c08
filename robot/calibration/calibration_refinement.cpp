#include "robot/calibration/calibration_refinement.h"

#include <ceres/ceres.h>
#include <ceres/rotation.h>

#include <array>
#include <cmath>
#include <stdexcept>

#include "common/camera/lens_distortion.h"

namespace lineloc {

namespace {

// Parameter blocks: intrinsics [fx fy cx cy skew], distortion [k1 k2 p1 p2 k3],
// per view rotation vector [3] and translation [3].
enum Intrinsic { kFx, kFy, kCx, kCy, kSkew, kIntrinsicCount };
using Pose = std::array<double, 6>;

// Residual m_ij - m(K, k, R_i, t_i, M_j) of one model point in one view.
// With a fixed aspect ratio fy = fx / aspect_ratio and the fy slot is unused.
class ModelPointReprojection {
 public:
  ModelPointReprojection(const Eigen::Vector2d& model_point, const Eigen::Vector2d& image_point,
                         double fixed_aspect_ratio)
      : model_point_(model_point),
        image_point_(image_point),
        fixed_aspect_ratio_(fixed_aspect_ratio) {}

  template <typename T>
  bool operator()(const T* intrinsics, const T* distortion, const T* rotation, const T* translation,
                  T* residual) const {
    const T M[3] = {T(model_point_.x()), T(model_point_.y()), T(0.0)};
    T p[3];
    ceres::AngleAxisRotatePoint(rotation, M, p);
    const Eigen::Matrix<T, 2, 1> normalised((p[0] + translation[0]) / (p[2] + translation[2]),
                                            (p[1] + translation[1]) / (p[2] + translation[2]));
    const Eigen::Matrix<T, 2, 1> x =
        distortNormalised<T>(normalised, distortion, kDistortionCoefficients);
    const T fy =
        fixed_aspect_ratio_ > 0.0 ? intrinsics[kFx] / fixed_aspect_ratio_ : intrinsics[kFy];
    residual[0] = T(image_point_.x()) -
                  (intrinsics[kFx] * x.x() + intrinsics[kSkew] * x.y() + intrinsics[kCx]);
    residual[1] = T(image_point_.y()) - (fy * x.y() + intrinsics[kCy]);
    return true;
  }

 private:
  Eigen::Vector2d model_point_;
  Eigen::Vector2d image_point_;
  double fixed_aspect_ratio_;
};

std::vector<int> fixedIntrinsics(const CalibrationOptions& options) {
  std::vector<int> fixed;
  if (options.fix_aspect_ratio) {
    fixed.push_back(kFy);
  }
  if (options.fix_principal_point) {
    fixed.push_back(kCx);
    fixed.push_back(kCy);
  }
  if (options.fix_skew) {
    fixed.push_back(kSkew);
  }
  return fixed;
}

std::vector<int> fixedDistortion(DistortionModel model) {
  if (model == DistortionModel::kRadialK1K2) {
    return {2, 3, 4};
  }
  return {};
}

// A block held entirely, partly or not at all; returns its free dimension.
int holdFixed(ceres::Problem& problem, double* block, int size, const std::vector<int>& fixed) {
  if (static_cast<int>(fixed.size()) == size) {
    problem.SetParameterBlockConstant(block);
    return 0;
  }
  if (!fixed.empty()) {
    problem.SetManifold(block, new ceres::SubsetManifold(size, fixed));
  }
  return size - static_cast<int>(fixed.size());
}

std::array<double, kIntrinsicCount> intrinsicsOf(const PinholeCamera& camera,
                                                 const CalibrationOptions& options) {
  std::array<double, kIntrinsicCount> intrinsics = {camera.fx, camera.fy, camera.cx, camera.cy,
                                                    camera.skew};
  if (options.fix_skew) {
    intrinsics[kSkew] = 0.0;
  }
  if (options.fix_aspect_ratio) {
    intrinsics[kFy] = intrinsics[kFx] / options.aspect_ratio;
  }
  return intrinsics;
}

Pose poseOf(const Eigen::Isometry3d& T_camera_model) {
  Pose pose;
  const Eigen::Matrix3d R = T_camera_model.linear();
  ceres::RotationMatrixToAngleAxis(ceres::ColumnMajorAdapter3x3(R.data()), pose.data());
  Eigen::Map<Eigen::Vector3d>(pose.data() + 3) = T_camera_model.translation();
  return pose;
}

Eigen::Isometry3d isometryOf(const Pose& pose) {
  Eigen::Matrix3d R;
  ceres::AngleAxisToRotationMatrix(pose.data(), ceres::ColumnMajorAdapter3x3(R.data()));
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = R;
  T.translation() = Eigen::Map<const Eigen::Vector3d>(pose.data() + 3);
  return T;
}

// sqrt(diag(variance_scale * Cov)) of an N-parameter block.
template <int N>
Eigen::Matrix<double, N, 1> blockStdDev(const ceres::Covariance& covariance, const double* block,
                                        double variance_scale) {
  Eigen::Matrix<double, N, N, Eigen::RowMajor> block_covariance;
  covariance.GetCovarianceBlock(block, block, block_covariance.data());
  return (variance_scale * block_covariance.diagonal()).cwiseMax(0.0).cwiseSqrt();
}

// The parameters Ceres optimises, in place.
struct ParameterBlocks {
  std::array<double, kIntrinsicCount> intrinsics{};
  std::array<double, kDistortionCoefficients> distortion{};
  std::vector<Pose> poses;
};

ParameterBlocks parameterBlocksOf(const CalibrationState& initial,
                                  const CalibrationOptions& options) {
  ParameterBlocks blocks;
  blocks.intrinsics = intrinsicsOf(initial.calibration.camera, options);
  std::copy_n(initial.calibration.distortion.begin(),
              std::min<size_t>(kDistortionCoefficients, initial.calibration.distortion.size()),
              blocks.distortion.begin());
  for (const Eigen::Isometry3d& T : initial.T_camera_model) {
    blocks.poses.push_back(poseOf(T));
  }
  return blocks;
}

// Adds one residual per model point and view and holds the fixed parameters;
// returns the number of free parameters.
int buildProblem(const PlanarViews& views, const CalibrationOptions& options, RefinementScope scope,
                 ParameterBlocks* blocks, ceres::Problem* problem) {
  const double fixed_aspect_ratio = options.fix_aspect_ratio ? options.aspect_ratio : 0.0;
  for (size_t view = 0; view < views.image_points.size(); ++view) {
    double* pose = blocks->poses[view].data();
    for (size_t i = 0; i < views.model_points.size(); ++i) {
      problem->AddResidualBlock(
          new ceres::AutoDiffCostFunction<ModelPointReprojection, 2, kIntrinsicCount,
                                          kDistortionCoefficients, 3, 3>(new ModelPointReprojection(
              views.model_points[i], views.image_points[view][i], fixed_aspect_ratio)),
          nullptr, blocks->intrinsics.data(), blocks->distortion.data(), pose, pose + 3);
    }
  }
  const int pose_parameters = 6 * static_cast<int>(blocks->poses.size());
  if (scope == RefinementScope::kPosesOnly) {
    problem->SetParameterBlockConstant(blocks->intrinsics.data());
    problem->SetParameterBlockConstant(blocks->distortion.data());
    return pose_parameters;
  }
  return pose_parameters +
         holdFixed(*problem, blocks->intrinsics.data(), kIntrinsicCount, fixedIntrinsics(options)) +
         holdFixed(*problem, blocks->distortion.data(), kDistortionCoefficients,
                   fixedDistortion(options.distortion_model));
}

ceres::Solver::Options solverOptions(const CalibrationOptions& options) {
  ceres::Solver::Options solver_options;
  solver_options.linear_solver_type = ceres::DENSE_SCHUR;
  solver_options.max_num_iterations = options.max_iterations;
  solver_options.function_tolerance = 1e-14;
  solver_options.gradient_tolerance = 1e-14;
  solver_options.parameter_tolerance = 1e-12;
  solver_options.num_threads = 1;
  return solver_options;
}

RefinementStatus statusOf(const ceres::Solver::Summary& summary) {
  if (!std::isfinite(summary.final_cost)) {
    return RefinementStatus::kDiverged;
  }
  if (summary.termination_type == ceres::CONVERGENCE) {
    return RefinementStatus::kConverged;
  }
  if (summary.termination_type == ceres::NO_CONVERGENCE) {
    return RefinementStatus::kNoConvergence;
  }
  return RefinementStatus::kDiverged;
}

CalibrationState stateOf(const ParameterBlocks& blocks, const PinholeCamera& initial_camera,
                         const CalibrationOptions& options) {
  CalibrationState state;
  PinholeCamera& camera = state.calibration.camera;
  camera = initial_camera;
  camera.fx = blocks.intrinsics[kFx];
  camera.fy = options.fix_aspect_ratio ? camera.fx / options.aspect_ratio : blocks.intrinsics[kFy];
  camera.cx = blocks.intrinsics[kCx];
  camera.cy = blocks.intrinsics[kCy];
  camera.skew = blocks.intrinsics[kSkew];
  state.calibration.distortion.assign(blocks.distortion.begin(), blocks.distortion.end());
  for (const Pose& pose : blocks.poses) {
    state.T_camera_model.push_back(isometryOf(pose));
  }
  return state;
}

// Cov = variance (J^T J)^-1 over the free parameters (zero for fixed ones);
// not available when J^T J is rank deficient.
CalibrationUncertainty uncertaintyOf(const ParameterBlocks& blocks, double variance,
                                     const CalibrationOptions& options, RefinementScope scope,
                                     ceres::Problem* problem) {
  ceres::Covariance::Options covariance_options;
  covariance_options.algorithm_type = ceres::DENSE_SVD;
  covariance_options.min_reciprocal_condition_number = 1e-14;
  ceres::Covariance covariance(covariance_options);
  std::vector<std::pair<const double*, const double*>> wanted;
  if (scope == RefinementScope::kAllParameters) {
    wanted.emplace_back(blocks.intrinsics.data(), blocks.intrinsics.data());
    wanted.emplace_back(blocks.distortion.data(), blocks.distortion.data());
  }
  for (const Pose& pose : blocks.poses) {
    wanted.emplace_back(pose.data(), pose.data());
    wanted.emplace_back(pose.data() + 3, pose.data() + 3);
  }
  CalibrationUncertainty uncertainty;
  if (!covariance.Compute(wanted, problem)) {
    return uncertainty;
  }
  uncertainty.available = true;
  uncertainty.noise_sigma_px = std::sqrt(variance);
  if (scope == RefinementScope::kAllParameters) {
    uncertainty.intrinsics_std_dev =
        blockStdDev<kIntrinsicCount>(covariance, blocks.intrinsics.data(), variance);
    uncertainty.distortion_std_dev =
        blockStdDev<kDistortionCoefficients>(covariance, blocks.distortion.data(), variance);
    if (options.fix_aspect_ratio) {
      uncertainty.intrinsics_std_dev(kFy) =
          uncertainty.intrinsics_std_dev(kFx) / options.aspect_ratio;
    }
  }
  for (const Pose& pose : blocks.poses) {
    Eigen::Matrix<double, 6, 1> pose_std_dev;
    pose_std_dev << blockStdDev<3>(covariance, pose.data(), variance),
        blockStdDev<3>(covariance, pose.data() + 3, variance);
    uncertainty.pose_std_dev.push_back(pose_std_dev);
  }
  return uncertainty;
}

}  // namespace

const char* toString(RefinementStatus status) {
  switch (status) {
    case RefinementStatus::kConverged:
      return "converged";
    case RefinementStatus::kNoConvergence:
      return "no convergence within the iteration limit";
    case RefinementStatus::kDiverged:
      return "diverged";
  }
  return "unknown";
}

RefinementResult refineCalibration(const PlanarViews& views, const CalibrationState& initial,
                                   const CalibrationOptions& options, RefinementScope scope) {
  if (initial.T_camera_model.size() != views.image_points.size()) {
    throw std::invalid_argument("calibration refinement: one initial pose per view is needed");
  }
  ParameterBlocks blocks = parameterBlocksOf(initial, options);
  ceres::Problem problem;
  const int free_parameters = buildProblem(views, options, scope, &blocks, &problem);
  ceres::Solver::Summary summary;
  ceres::Solve(solverOptions(options), &problem, &summary);

  RefinementResult result;
  result.iterations = static_cast<int>(summary.iterations.size());
  result.status = statusOf(summary);
  if (result.status == RefinementStatus::kDiverged) {
    return result;
  }
  result.state = stateOf(blocks, initial.calibration.camera, options);
  const int observations =
      2 * static_cast<int>(views.model_points.size() * views.image_points.size());
  if (observations > free_parameters) {
    const double variance = 2.0 * summary.final_cost / (observations - free_parameters);
    result.uncertainty = uncertaintyOf(blocks, variance, options, scope, &problem);
  }
  return result;
}

}  // namespace lineloc
