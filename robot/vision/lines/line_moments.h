// Total-least-squares straight line from the first and second moments of 2D
// points, and the uncertainty of its normal offset and angle from the fit
// residuals (Persa & Jonker §3: every split-and-merge piece is refitted).
//
// With centroid c and scatter S = (1/n) sum (p - c)(p - c)^T of eigenvalues
// lambda_min <= lambda_max, the line passes through c along the major axis
// d (the eigenvector of lambda_max, at theta = atan2(2 Sxy, Sxx - Syy) / 2), and the
// residual sum of squares is n lambda_min. With sigma^2 = n lambda_min / (n - 2)
// and n_eff = n / points_per_sample independent points (neighbouring edge
// points share the smoothing kernel, so their errors are correlated):
//   sigma_offset = sigma / sqrt(n_eff)                  (normal offset at c)
//   sigma_angle  = sigma / sqrt(n_eff lambda_max)       (radians)
// and the normal error at a point c + t d is sigma_offset^2 + t^2 sigma_angle^2.
// Moments add and subtract, so pieces merge in O(1), and a polyline's
// running sums give the moments of any run of its points in O(1).
#pragma once

#include <Eigen/Core>
#include <span>
#include <vector>

namespace lineloc {

struct PointMoments {
  double n = 0.0;
  double sx = 0.0, sy = 0.0;
  double sxx = 0.0, sxy = 0.0, syy = 0.0;

  void add(const Eigen::Vector2f& p) {
    const double x = p.x();
    const double y = p.y();
    n += 1.0;
    sx += x;
    sy += y;
    sxx += x * x;
    sxy += x * y;
    syy += y * y;
  }
  PointMoments& operator+=(const PointMoments& other);
  PointMoments operator-(const PointMoments& other) const;
};

// Running sums of a polyline's moments: prefix[i] holds points [0, i), so
// the moments of points [a, b) are prefix[b] - prefix[a], in O(1).
void cumulativeMoments(std::span<const Eigen::Vector2f> points, std::vector<PointMoments>& prefix);

enum class LineFitStatus { kOk, kTooFewPoints, kDegenerate };

struct LineFit {
  LineFitStatus status = LineFitStatus::kTooFewPoints;
  Eigen::Vector2d centroid = Eigen::Vector2d::Zero();
  // Unit direction with y >= 0 (angle in [0, pi)) and normal (-d.y, d.x).
  Eigen::Vector2d direction = Eigen::Vector2d::UnitX();
  Eigen::Vector2d normal = Eigen::Vector2d::UnitY();
  double residual_sigma_px = 0.0;  // of one point's distance from the line
  double sigma_offset_px = 0.0;
  double sigma_angle_rad = 0.0;

  // Signed distance of p from the line, along the normal.
  double distance(const Eigen::Vector2d& p) const { return normal.dot(p - centroid); }
  // Coordinate of p along the line, from the centroid.
  double along(const Eigen::Vector2d& p) const { return direction.dot(p - centroid); }
  // Variance of the line's normal position at `along` from the centroid.
  double normalVariance(double along) const {
    return sigma_offset_px * sigma_offset_px + along * along * sigma_angle_rad * sigma_angle_rad;
  }
};

struct LineFitOptions {
  double points_per_sample = 2.0;  // correlated edge points per independent one
  double min_sigma_px = 0.05;      // floor of the residual sigma (interpolation limit)
};

// kTooFewPoints below 3 points, kDegenerate when all points coincide.
LineFit fitLine(const PointMoments& moments, const LineFitOptions& options);

}  // namespace lineloc
