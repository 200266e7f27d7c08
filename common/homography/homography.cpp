#include "common/homography/homography.h"

#include <ceres/tiny_solver.h>

#include <Eigen/Eigenvalues>
#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace lineloc {

namespace {

// Scatter of normalised points below this eigenvalue ratio: the points lie on
// a line to within 1e-4 of their spread (e.g. 0.06 px over a 640 px board).
constexpr double kCollinearEigenvalueRatio = 1e-8;
// sigma_8 / sigma_1 of L below this: L x = 0 has more than one solution.
constexpr double kRankDeficientSingularValueRatio = 1e-10;
// |det H| / ||H||_F^3 below this (normalised coordinates): H is singular.
constexpr double kSingularDeterminant = 1e-12;
constexpr double kVanishingScale = 1e-12;

// Hartley normalisation p_n = scale (p - centroid), mean ||p_n|| = sqrt(2).
struct Normalisation {
  Eigen::Vector2d centroid = Eigen::Vector2d::Zero();
  double scale = 1.0;

  Eigen::Vector2d apply(const Eigen::Vector2d& p) const { return scale * (p - centroid); }
  Eigen::Matrix3d matrix() const {
    Eigen::Matrix3d T;
    T << scale, 0.0, -scale * centroid.x(), 0.0, scale, -scale * centroid.y(), 0.0, 0.0, 1.0;
    return T;
  }
  Eigen::Matrix3d inverseMatrix() const {
    Eigen::Matrix3d T_inverse;
    T_inverse << 1.0 / scale, 0.0, centroid.x(), 0.0, 1.0 / scale, centroid.y(), 0.0, 0.0, 1.0;
    return T_inverse;
  }
};

struct NormalisedPoints {
  Normalisation normalisation;
  std::vector<Eigen::Vector2d> points;
};

// Returns false for coincident or collinear points.
bool normalise(const std::vector<Eigen::Vector2d>& points, NormalisedPoints* result) {
  Eigen::Vector2d centroid = Eigen::Vector2d::Zero();
  for (const Eigen::Vector2d& p : points) {
    centroid += p;
  }
  centroid /= static_cast<double>(points.size());
  double mean_distance = 0.0;
  for (const Eigen::Vector2d& p : points) {
    mean_distance += (p - centroid).norm();
  }
  mean_distance /= static_cast<double>(points.size());
  if (!(mean_distance > 0.0)) {
    return false;
  }
  result->normalisation = {centroid, std::sqrt(2.0) / mean_distance};
  result->points.clear();
  result->points.reserve(points.size());
  Eigen::Matrix2d scatter = Eigen::Matrix2d::Zero();
  for (const Eigen::Vector2d& p : points) {
    result->points.push_back(result->normalisation.apply(p));
    scatter += result->points.back() * result->points.back().transpose();
  }
  const Eigen::Vector2d eigenvalues =
      Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d>(scatter, Eigen::EigenvaluesOnly).eigenvalues();
  return eigenvalues(0) > kCollinearEigenvalueRatio * eigenvalues(1);
}

struct NormalisedProblem {
  NormalisedPoints model;
  NormalisedPoints image;
};

HomographyEstimate failure(HomographyStatus status) {
  HomographyEstimate estimate;
  estimate.status = status;
  return estimate;
}

// Checks sizes and values and normalises both point sets; returns kOk or why not.
HomographyStatus prepare(const std::vector<Eigen::Vector2d>& model_points,
                         const std::vector<Eigen::Vector2d>& image_points,
                         NormalisedProblem* problem) {
  if (model_points.size() != image_points.size()) {
    throw std::invalid_argument("homography: " + std::to_string(model_points.size()) +
                                " model points but " + std::to_string(image_points.size()) +
                                " image points");
  }
  if (model_points.size() < 4) {
    return HomographyStatus::kNotEnoughPoints;
  }
  const auto is_finite = [](const Eigen::Vector2d& p) { return p.allFinite(); };
  if (!std::all_of(model_points.begin(), model_points.end(), is_finite) ||
      !std::all_of(image_points.begin(), image_points.end(), is_finite)) {
    return HomographyStatus::kNonFinite;
  }
  if (!normalise(model_points, &problem->model) || !normalise(image_points, &problem->image)) {
    return HomographyStatus::kDegenerate;
  }
  return HomographyStatus::kOk;
}

// True when H_n is invertible and maps every model point to a finite image
// point on the same side of the vanishing line.
bool isProperHomography(const Eigen::Matrix3d& H_normalised,
                        const std::vector<Eigen::Vector2d>& model_normalised) {
  const double norm = H_normalised.norm();
  if (!(std::abs(H_normalised.determinant()) > kSingularDeterminant * norm * norm * norm)) {
    return false;
  }
  const double first_w = H_normalised.row(2).dot(model_normalised.front().homogeneous());
  return std::all_of(
      model_normalised.begin(), model_normalised.end(), [&](const Eigen::Vector2d& M) {
        return H_normalised.row(2).dot(M.homogeneous()) * first_w > kVanishingScale * norm * norm;
      });
}

Eigen::Matrix3d scaleConventionally(const Eigen::Matrix3d& H) {
  const double norm = H.norm();
  if (std::abs(H(2, 2)) > kVanishingScale * norm) {
    return H / H(2, 2);
  }
  return H / norm;
}

HomographyEstimate finish(const Eigen::Matrix3d& H_normalised, const NormalisedProblem& problem,
                          const std::vector<Eigen::Vector2d>& model_points,
                          const std::vector<Eigen::Vector2d>& image_points) {
  if (!H_normalised.allFinite()) {
    return failure(HomographyStatus::kNonFinite);
  }
  if (!isProperHomography(H_normalised, problem.model.points)) {
    return failure(HomographyStatus::kDegenerate);
  }
  HomographyEstimate estimate;
  estimate.status = HomographyStatus::kOk;
  estimate.H = scaleConventionally(problem.image.normalisation.inverseMatrix() * H_normalised *
                                   problem.model.normalisation.matrix());
  double squared_error = 0.0;
  for (size_t i = 0; i < model_points.size(); ++i) {
    squared_error += (applyHomography(estimate.H, model_points[i]) - image_points[i]).squaredNorm();
  }
  estimate.rms_error = std::sqrt(squared_error / static_cast<double>(model_points.size()));
  return estimate;
}

// Zhang eq. 2 on normalised points: two rows of L per correspondence,
// [M^T 0 -u M^T; 0 M^T -v M^T] x = 0 with M = [X Y 1]^T, x = vec(H) row-major.
// Returns a zero matrix when the solution is not unique.
Eigen::Matrix3d solveDlt(const NormalisedProblem& problem) {
  const size_t n = problem.model.points.size();
  Eigen::MatrixXd L = Eigen::MatrixXd::Zero(2 * static_cast<Eigen::Index>(n), 9);
  for (size_t i = 0; i < n; ++i) {
    const Eigen::RowVector3d M = problem.model.points[i].homogeneous().transpose();
    const Eigen::Vector2d& m = problem.image.points[i];
    const Eigen::Index row = 2 * static_cast<Eigen::Index>(i);
    L.block<1, 3>(row, 0) = M;
    L.block<1, 3>(row, 6) = -m.x() * M;
    L.block<1, 3>(row + 1, 3) = M;
    L.block<1, 3>(row + 1, 6) = -m.y() * M;
  }
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(L, Eigen::ComputeFullV);
  const Eigen::VectorXd& singular_values = svd.singularValues();
  if (singular_values.size() >= 8 &&
      !(singular_values(7) > kRankDeficientSingularValueRatio * singular_values(0))) {
    return Eigen::Matrix3d::Zero();
  }
  const Eigen::Matrix<double, 9, 1> x = svd.matrixV().col(8);
  return Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(x.data());
}

// Reprojection error of Zhang eq. 1 for ceres::TinySolver, on normalised
// points, in image units: r_i = (proj(H_n M_i) - m_i) / s_image. The entry of
// H_n with the largest magnitude is held fixed (it removes the scale freedom);
// the other eight are the parameters.
class HomographyReprojectionError {
 public:
  using Scalar = double;
  enum { NUM_RESIDUALS = Eigen::Dynamic, NUM_PARAMETERS = 8 };

  HomographyReprojectionError(const NormalisedProblem& problem, const Eigen::Matrix3d& H_start)
      : problem_(problem),
        image_units_per_normalised_unit_(1.0 / problem.image.normalisation.scale) {
    Eigen::Map<const Eigen::Matrix<double, 9, 1>>(H_start.data())
        .cwiseAbs()
        .maxCoeff(&fixed_index_);
    fixed_value_ = H_start.data()[fixed_index_];
  }

  int NumResiduals() const { return 2 * static_cast<int>(problem_.model.points.size()); }

  Eigen::Matrix<double, 8, 1> parametersOf(const Eigen::Matrix3d& H) const {
    Eigen::Matrix<double, 8, 1> parameters;
    for (int i = 0, k = 0; i < 9; ++i) {
      if (i != fixed_index_) {
        parameters(k++) = H.data()[i];
      }
    }
    return parameters;
  }

  Eigen::Matrix3d homographyOf(const double* parameters) const {
    Eigen::Matrix3d H;
    for (int i = 0, k = 0; i < 9; ++i) {
      H.data()[i] = i == fixed_index_ ? fixed_value_ : parameters[k++];
    }
    return H;
  }

  // Jacobian (column-major, NumResiduals x 8) of u = p0/p2, v = p1/p2 with
  // p = H M: du/dH_row0 = M^T/p2, dv/dH_row1 = M^T/p2,
  // du/dH_row2 = -u M^T/p2, dv/dH_row2 = -v M^T/p2.
  bool operator()(const double* parameters, double* residuals, double* jacobian) const {
    const Eigen::Matrix3d H = homographyOf(parameters);
    const int n = static_cast<int>(problem_.model.points.size());
    Eigen::Map<Eigen::MatrixXd> J(jacobian, jacobian ? 2 * n : 0, jacobian ? 8 : 0);
    for (int i = 0; i < n; ++i) {
      const Eigen::Vector3d M = problem_.model.points[i].homogeneous();
      // A step through the vanishing line gives non-finite residuals, which
      // the solver rejects.
      const Eigen::Vector3d p = H * M;
      const Eigen::Vector2d projected = p.hnormalized();
      const Eigen::Vector2d residual =
          (projected - problem_.image.points[i]) * image_units_per_normalised_unit_;
      residuals[2 * i] = residual.x();
      residuals[2 * i + 1] = residual.y();
      if (jacobian == nullptr) {
        continue;
      }
      const double w = image_units_per_normalised_unit_ / p.z();
      Eigen::Matrix<double, 2, 9> J_H = Eigen::Matrix<double, 2, 9>::Zero();
      for (int c = 0; c < 3; ++c) {
        // H.data() is column-major: entry (r, c) is at 3 c + r.
        J_H(0, 3 * c + 0) = w * M(c);
        J_H(1, 3 * c + 1) = w * M(c);
        J_H(0, 3 * c + 2) = -w * projected.x() * M(c);
        J_H(1, 3 * c + 2) = -w * projected.y() * M(c);
      }
      for (int j = 0, k = 0; j < 9; ++j) {
        if (j != fixed_index_) {
          J.block<2, 1>(2 * i, k++) = J_H.col(j);
        }
      }
    }
    return true;
  }

 private:
  const NormalisedProblem& problem_;
  double image_units_per_normalised_unit_;
  Eigen::Index fixed_index_ = 8;
  double fixed_value_ = 1.0;
};

Eigen::Matrix3d refineNormalised(const NormalisedProblem& problem, const Eigen::Matrix3d& H_start) {
  const HomographyReprojectionError error(problem, H_start / H_start.norm());
  ceres::TinySolver<HomographyReprojectionError> solver;
  solver.options.max_num_iterations = 100;
  solver.options.gradient_tolerance = 1e-14;
  solver.options.parameter_tolerance = 1e-14;
  solver.options.function_tolerance = 1e-20;
  Eigen::Matrix<double, 8, 1> parameters = error.parametersOf(H_start / H_start.norm());
  solver.Solve(error, &parameters);
  return error.homographyOf(parameters.data());
}

}  // namespace

const char* toString(HomographyStatus status) {
  switch (status) {
    case HomographyStatus::kOk:
      return "ok";
    case HomographyStatus::kNotEnoughPoints:
      return "not enough points (need 4)";
    case HomographyStatus::kDegenerate:
      return "degenerate (coincident or collinear points, or a singular homography)";
    case HomographyStatus::kNonFinite:
      return "non-finite coordinates";
  }
  return "unknown";
}

Eigen::Vector2d applyHomography(const Eigen::Matrix3d& H, const Eigen::Vector2d& p) {
  return (H * p.homogeneous()).hnormalized();
}

HomographyEstimate estimateHomographyDlt(const std::vector<Eigen::Vector2d>& model_points,
                                         const std::vector<Eigen::Vector2d>& image_points) {
  NormalisedProblem problem;
  const HomographyStatus status = prepare(model_points, image_points, &problem);
  if (status != HomographyStatus::kOk) {
    return failure(status);
  }
  return finish(solveDlt(problem), problem, model_points, image_points);
}

HomographyEstimate refineHomography(const std::vector<Eigen::Vector2d>& model_points,
                                    const std::vector<Eigen::Vector2d>& image_points,
                                    const Eigen::Matrix3d& H_initial) {
  NormalisedProblem problem;
  const HomographyStatus status = prepare(model_points, image_points, &problem);
  if (status != HomographyStatus::kOk) {
    return failure(status);
  }
  if (!H_initial.allFinite()) {
    return failure(HomographyStatus::kNonFinite);
  }
  const Eigen::Matrix3d H_start = problem.image.normalisation.matrix() * H_initial *
                                  problem.model.normalisation.inverseMatrix();
  if (!isProperHomography(H_start, problem.model.points)) {
    return failure(HomographyStatus::kDegenerate);
  }
  return finish(refineNormalised(problem, H_start), problem, model_points, image_points);
}

HomographyEstimate estimateHomography(const std::vector<Eigen::Vector2d>& model_points,
                                      const std::vector<Eigen::Vector2d>& image_points) {
  const HomographyEstimate dlt = estimateHomographyDlt(model_points, image_points);
  if (dlt.status != HomographyStatus::kOk) {
    return dlt;
  }
  return refineHomography(model_points, image_points, dlt.H);
}

}  // namespace lineloc
