// Closed-form intrinsics from plane homographies, Zhang (ICCV 1999) §3.1 and
// Appendix B.
//
// With B = K^-T K^-1 (symmetric, b = [B11 B12 B22 B13 B23 B33]^T) each
// homography H = [h1 h2 h3] gives two equations in b (Zhang eq. 3):
//
//   [ v12^T          ]
//   [ (v11 - v22)^T  ] b = 0,
//   v_ij = [hi1 hj1, hi1 hj2 + hi2 hj1, hi2 hj2, hi3 hj1 + hi1 hj3, hi3 hj2 + hi2 hj3, hi3 hj3]^T,
//
// stacked into V b = 0 and solved as the right singular vector of V with the
// smallest singular value; K follows from B by Cholesky-like formulas. A zero
// skew adds the row [0 1 0 0 0 0]. The homographies are first moved to image
// coordinates centred and scaled by the image size, which keeps V well
// conditioned; K is mapped back at the end.
#pragma once

#include <Eigen/Core>
#include <vector>

namespace lineloc {

enum class ClosedFormStatus {
  kOk,
  kNotEnoughViews,  // fewer than 3 views (2 with zero skew)
  kDegenerate,      // V b = 0 has no unique solution, or B is not positive definite
};

struct ClosedFormIntrinsics {
  ClosedFormStatus status = ClosedFormStatus::kNotEnoughViews;
  // Upper triangular [fx skew cx; 0 fy cy; 0 0 1]; identity unless kOk.
  Eigen::Matrix3d K = Eigen::Matrix3d::Identity();
};

ClosedFormIntrinsics estimateIntrinsicsClosedForm(const std::vector<Eigen::Matrix3d>& homographies,
                                                  bool zero_skew, int image_width,
                                                  int image_height);

}  // namespace lineloc
