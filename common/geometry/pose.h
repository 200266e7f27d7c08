// Rigid poses with covariance, the one representation every module shares.
//
// A pose T_a_b maps points from frame b to frame a: p_a = R_a_b p_b + t_a_b.
// Its uncertainty is the covariance of the error vector e = [dp; dtheta] in
// frame a, with t = t_est + dp and R = Exp(dtheta) R_est (left perturbation,
// Solà, "A micro Lie theory for state estimation in robotics", 2018, eq. 27).
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <string>
#include <vector>

namespace lineloc {

using Matrix6d = Eigen::Matrix<double, 6, 6>;

struct PoseWithCovariance {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  Matrix6d covariance = Matrix6d::Identity();
};

// [v]x, the cross-product matrix: skew(a) b = a x b.
Eigen::Matrix3d skew(const Eigen::Vector3d& v);

// Builds a pose from translation (x, y, z) and unit quaternion (x, y, z, w).
Eigen::Isometry3d makePose(const Eigen::Vector3d& translation, const Eigen::Quaterniond& rotation);

// Translation-then-rotation standard deviations on the diagonal: diag(sp^2 I3, sr^2 I3).
Matrix6d diagonalPoseCovariance(double position_sigma_m, double rotation_sigma_rad);

// The error vector e = [dp; dtheta] taking `estimate` to `truth` in the
// convention above: t_truth = t_est + dp, R_truth = Exp(dtheta) R_est.
Eigen::Matrix<double, 6, 1> poseError(const Eigen::Isometry3d& estimate,
                                      const Eigen::Isometry3d& truth);

// `pose` moved by the error vector e: t + dp, Exp(dtheta) R.
Eigen::Isometry3d applyPoseError(const Eigen::Isometry3d& pose,
                                 const Eigen::Matrix<double, 6, 1>& error);

// T_world_a T_a_b for an exactly known motion T_a_b (dead reckoning over a
// fraction of a second) with its covariance carried along: t_b = t_a + R_a t_ab
// with R_a = Exp(dtheta) R_a,est gives dp_b = dp_a - [l]x dtheta, l = R_a t_ab,
// and dtheta_b = dtheta, so Sigma_b = J Sigma_a J^T, J = [I, -[l]x; 0, I].
PoseWithCovariance composeExactMotion(const PoseWithCovariance& T_world_a,
                                      const Eigen::Isometry3d& T_a_b);

// T_b_a T_a_c for an exactly known change of world frame T_b_a: with t_c in
// b = R_b_a t_c + t_b_a and R = R_b_a Exp(dtheta) R_a_c = Exp(R_b_a dtheta)
// R_b_a R_a_c, the error turns with the frame, e_b = diag(R_b_a, R_b_a) e_a.
PoseWithCovariance changeWorldFrame(const Eigen::Isometry3d& T_b_a,
                                    const PoseWithCovariance& T_a_c);

// The pose in a world scaled by `factor` about its origin: t -> factor t, so
// dp -> factor dp and the position rows and columns of the covariance scale by
// factor (its position block by factor^2); the rotation is unchanged.
PoseWithCovariance scaledWorld(const PoseWithCovariance& pose, double factor);

// Two independent estimates of one pose combined by their information,
// linearised at `a`: Sigma = (Sigma_a^-1 + Sigma_b^-1)^-1 and the pose a moved
// by Sigma Sigma_b^-1 e, e = poseError(a, b) (the Kalman update with b as the
// measurement).
PoseWithCovariance fusePoses(const PoseWithCovariance& a, const PoseWithCovariance& b);

// sum_i (x_i - mean)(x_i - mean)^T over pose error vectors: the sample
// covariance times n - 1, the jackknife's times (n - 1)^2 / n.
Matrix6d scatterAboutMean(const std::vector<Eigen::Matrix<double, 6, 1>>& samples);

// The smallest covariance at least as large as both a and b in every
// direction: with a = L L^T and L^-1 b L^-T = V D V^T, L V max(D, 1) V^T L^T.
// Infinite when a is not positive definite (it bounds nothing).
Matrix6d coveringCovariance(const Matrix6d& a, const Matrix6d& b);

// Standard deviation along a 3 x 3 covariance's largest principal axis.
double largestSigma(const Eigen::Matrix3d& covariance);

// Standard deviation along the position covariance's largest principal axis.
double largestPositionSigma(const Matrix6d& covariance);

// e^T Sigma^-1 e: the estimate's error in its own covariance, the normalized
// estimation error squared (Bar-Shalom, Li & Kirubarajan, "Estimation with
// Applications to Tracking and Navigation", 2001, §5.4.2); chi^2 with 6
// degrees of freedom for a consistent estimate.
double normalizedErrorSquared(const PoseWithCovariance& estimate, const Eigen::Isometry3d& truth);

// True when every entry of the pose and covariance is finite and the rotation is
// orthonormal to within `tolerance`.
bool isFinitePose(const PoseWithCovariance& pose, double tolerance = 1e-6);

// The 4x4 row-major matrix `entries` (16 numbers) as a rigid transform.
// Throws std::runtime_error naming `source` when there are not 16 finite
// numbers, the last row is not 0 0 0 1, or the rotation is not orthonormal
// with determinant +1 (within 1e-6).
Eigen::Isometry3d rigidTransform(const std::vector<double>& entries, const std::string& source);

}  // namespace lineloc
