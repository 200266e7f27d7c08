#include "robot/calibration/distortion_initialisation.h"

#include <Eigen/QR>

namespace lineloc {

namespace {

// Column-pivoted QR treats relative pivots below this as zero.
constexpr double kRankThreshold = 1e-10;

}  // namespace

std::optional<std::vector<double>> estimateDistortionLinear(
    const PlanarViews& views, const PinholeCamera& camera,
    const std::vector<Eigen::Isometry3d>& T_camera_model, DistortionModel model) {
  const int unknowns = model == DistortionModel::kRadialK1K2 ? 2 : kDistortionCoefficients;
  const Eigen::Index rows =
      2 * static_cast<Eigen::Index>(views.model_points.size() * views.image_points.size());
  Eigen::MatrixXd D(rows, unknowns);
  Eigen::VectorXd d(rows);
  Eigen::Index row = 0;
  for (size_t view = 0; view < views.image_points.size(); ++view) {
    for (size_t i = 0; i < views.model_points.size(); ++i) {
      const Eigen::Vector2d& M = views.model_points[i];
      const Eigen::Vector2d x =
          (T_camera_model[view] * Eigen::Vector3d(M.x(), M.y(), 0.0)).hnormalized();
      const double r2 = x.squaredNorm();
      // d(dx)/dk and d(dy)/dk in the order k1 k2 p1 p2 k3.
      Eigen::Matrix<double, 5, 1> dx_dk;
      Eigen::Matrix<double, 5, 1> dy_dk;
      dx_dk << x.x() * r2, x.x() * r2 * r2, 2.0 * x.x() * x.y(), r2 + 2.0 * x.x() * x.x(),
          x.x() * r2 * r2 * r2;
      dy_dk << x.y() * r2, x.y() * r2 * r2, r2 + 2.0 * x.y() * x.y(), 2.0 * x.x() * x.y(),
          x.y() * r2 * r2 * r2;
      const Eigen::Vector2d ideal = camera.project(x.homogeneous());
      const Eigen::Vector2d& measured = views.image_points[view][i];
      D.row(row) = (camera.fx * dx_dk + camera.skew * dy_dk).head(unknowns).transpose();
      D.row(row + 1) = (camera.fy * dy_dk).head(unknowns).transpose();
      d(row) = measured.x() - ideal.x();
      d(row + 1) = measured.y() - ideal.y();
      row += 2;
    }
  }
  Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(D);
  qr.setThreshold(kRankThreshold);
  if (qr.rank() < unknowns) {
    return std::nullopt;
  }
  const Eigen::VectorXd k = qr.solve(d);
  if (!k.allFinite()) {
    return std::nullopt;
  }
  std::vector<double> coefficients(kDistortionCoefficients, 0.0);
  for (int i = 0; i < unknowns; ++i) {
    coefficients[i] = k(i);
  }
  return coefficients;
}

}  // namespace lineloc
