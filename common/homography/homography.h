// Homography from a model plane to the image, as in Zhang, "Flexible Camera
// Calibration by Viewing a Plane from Unknown Orientations" (ICCV 1999), §2 and
// Appendix A:
//
//   s [u v 1]^T = H [X Y 1]^T                                      (model plane Z = 0)
//
// 1. Normalised DLT: both point sets are moved to their centroid and scaled to a
//    mean distance of sqrt(2) (Hartley, "In defence of the eight-point
//    algorithm", PAMI 1997); x = vec(H) is the right singular vector of L with
//    the smallest singular value, L x = 0 (Zhang eq. 2).
// 2. Maximum-likelihood refinement: Levenberg-Marquardt on the reprojection
//    error sum_i ||m_i - proj(H M_i)||^2 (Zhang eq. 1).
#pragma once

#include <Eigen/Core>
#include <vector>

namespace lineloc {

enum class HomographyStatus {
  kOk,
  kNotEnoughPoints,  // fewer than 4 correspondences
  kDegenerate,       // collinear or coincident points, or H singular
  kNonFinite,        // an input coordinate is NaN or infinite
};

const char* toString(HomographyStatus status);

struct HomographyEstimate {
  HomographyStatus status = HomographyStatus::kNotEnoughPoints;
  // image ~ H [model; 1], scaled so that H(2,2) = 1, or to unit Frobenius norm
  // when H(2,2) vanishes. Identity unless status is kOk.
  Eigen::Matrix3d H = Eigen::Matrix3d::Identity();
  // sqrt(sum_i ||m_i - proj(H M_i)||^2 / n), in image units.
  double rms_error = 0.0;
};

// proj(H [p; 1]): the point p mapped by H.
Eigen::Vector2d applyHomography(const Eigen::Matrix3d& H, const Eigen::Vector2d& p);

// Step 1 alone: normalised DLT (algebraic error).
// Throws std::invalid_argument when the two lists differ in length.
HomographyEstimate estimateHomographyDlt(const std::vector<Eigen::Vector2d>& model_points,
                                         const std::vector<Eigen::Vector2d>& image_points);

// Step 2 alone: refines H_initial by minimising the reprojection error in the
// image. Throws std::invalid_argument when the two lists differ in length.
HomographyEstimate refineHomography(const std::vector<Eigen::Vector2d>& model_points,
                                    const std::vector<Eigen::Vector2d>& image_points,
                                    const Eigen::Matrix3d& H_initial);

// Both steps: the maximum-likelihood homography under isotropic Gaussian image
// noise. Throws std::invalid_argument when the two lists differ in length.
HomographyEstimate estimateHomography(const std::vector<Eigen::Vector2d>& model_points,
                                      const std::vector<Eigen::Vector2d>& image_points);

}  // namespace lineloc
