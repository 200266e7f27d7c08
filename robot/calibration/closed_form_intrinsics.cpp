#include "robot/calibration/closed_form_intrinsics.h"

#include <Eigen/LU>
#include <Eigen/SVD>
#include <algorithm>
#include <cmath>

namespace lineloc {

namespace {

// sigma_5 / sigma_1 of V below this: b is not determined.
constexpr double kRankDeficientSingularValueRatio = 1e-12;

using Vector6d = Eigen::Matrix<double, 6, 1>;

Vector6d v(const Eigen::Matrix3d& H, int i, int j) {
  const Eigen::Vector3d hi = H.col(i);
  const Eigen::Vector3d hj = H.col(j);
  Vector6d result;
  result << hi(0) * hj(0), hi(0) * hj(1) + hi(1) * hj(0), hi(1) * hj(1),
      hi(2) * hj(0) + hi(0) * hj(2), hi(2) * hj(1) + hi(1) * hj(2), hi(2) * hj(2);
  return result;
}

// N maps pixels to coordinates centred on the image with unit half-size.
Eigen::Matrix3d imageNormalisation(int width, int height) {
  const double half_size = 0.5 * std::max(width, height);
  Eigen::Matrix3d N;
  N << 1.0 / half_size, 0.0, -0.5 * width / half_size, 0.0, 1.0 / half_size,
      -0.5 * height / half_size, 0.0, 0.0, 1.0;
  return N;
}

ClosedFormIntrinsics degenerate() {
  ClosedFormIntrinsics result;
  result.status = ClosedFormStatus::kDegenerate;
  return result;
}

}  // namespace

ClosedFormIntrinsics estimateIntrinsicsClosedForm(const std::vector<Eigen::Matrix3d>& homographies,
                                                  bool zero_skew, int image_width,
                                                  int image_height) {
  const int views = static_cast<int>(homographies.size());
  if (views < (zero_skew ? 2 : 3)) {
    return {};
  }
  const Eigen::Matrix3d N = imageNormalisation(image_width, image_height);
  Eigen::MatrixXd V(2 * views + (zero_skew ? 1 : 0), 6);
  for (int view = 0; view < views; ++view) {
    Eigen::Matrix3d H = N * homographies[view];
    H /= H.norm();
    V.row(2 * view) = v(H, 0, 1).transpose();
    V.row(2 * view + 1) = (v(H, 0, 0) - v(H, 1, 1)).transpose();
  }
  if (zero_skew) {
    V.row(2 * views) << 0.0, 1.0, 0.0, 0.0, 0.0, 0.0;
  }
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(V, Eigen::ComputeFullV);
  const Eigen::VectorXd& sigma = svd.singularValues();
  if (!(sigma(4) > kRankDeficientSingularValueRatio * sigma(0))) {
    return degenerate();
  }
  Vector6d b = svd.matrixV().col(5);
  if (b(0) < 0.0) {
    b = -b;
  }
  const double B11 = b(0), B12 = b(1), B22 = b(2), B13 = b(3), B23 = b(4), B33 = b(5);
  // Zhang, Appendix B.
  const double denominator = B11 * B22 - B12 * B12;
  if (!(denominator > 0.0)) {
    return degenerate();
  }
  const double v0 = (B12 * B13 - B11 * B23) / denominator;
  const double lambda = B33 - (B13 * B13 + v0 * (B12 * B13 - B11 * B23)) / B11;
  if (!(lambda / B11 > 0.0)) {
    return degenerate();
  }
  const double alpha = std::sqrt(lambda / B11);
  const double beta = std::sqrt(lambda * B11 / denominator);
  const double gamma = zero_skew ? 0.0 : -B12 * alpha * alpha * beta / lambda;
  const double u0 = gamma * v0 / beta - B13 * alpha * alpha / lambda;
  Eigen::Matrix3d K_normalised;
  K_normalised << alpha, gamma, u0, 0.0, beta, v0, 0.0, 0.0, 1.0;
  ClosedFormIntrinsics result;
  result.status = ClosedFormStatus::kOk;
  result.K = N.inverse() * K_normalised;
  if (!result.K.allFinite()) {
    return degenerate();
  }
  return result;
}

}  // namespace lineloc
