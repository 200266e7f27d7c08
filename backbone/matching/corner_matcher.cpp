#include "backbone/matching/corner_matcher.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include "backbone/matching/line_matcher.h"

namespace lineloc {
namespace {

double largestEigenvalue(const Eigen::Matrix2d& covariance) {
  const double half_trace = 0.5 * covariance.trace();
  return half_trace + std::sqrt(std::max(0.0, half_trace * half_trace - covariance.determinant()));
}

// The image corners sorted by x, so a gate's candidates are one run of them.
class CornersByColumn {
 public:
  explicit CornersByColumn(const std::vector<ImageCorner>& corners) : corners_(corners) {
    order_.resize(corners.size());
    std::iota(order_.begin(), order_.end(), 0);
    std::sort(order_.begin(), order_.end(),
              [&](int a, int b) { return corners[a].position.x() < corners[b].position.x(); });
    for (const ImageCorner& corner : corners) {
      max_variance_px2_ =
          std::max(max_variance_px2_, largestEigenvalue(corner.covariance.cast<double>()));
    }
  }

  // The best and second best chi^2 (and the best's index) of the image
  // corners within the gate of a model corner projected to `predicted` with
  // covariance `covariance` (floor included).
  struct Nearest {
    int index = -1;
    double chi2 = std::numeric_limits<double>::infinity();
    double second_chi2 = std::numeric_limits<double>::infinity();
  };

  Nearest nearest(const Eigen::Vector2d& predicted, const Eigen::Matrix2d& covariance,
                  double gate_chi2) const {
    const double reach_px =
        std::sqrt(gate_chi2 * (largestEigenvalue(covariance) + max_variance_px2_));
    auto it =
        std::lower_bound(order_.begin(), order_.end(), predicted.x() - reach_px,
                         [&](int index, double x) { return corners_[index].position.x() < x; });
    Nearest found;
    for (; it != order_.end() && corners_[*it].position.x() <= predicted.x() + reach_px; ++it) {
      const ImageCorner& corner = corners_[*it];
      const Eigen::Vector2d offset = corner.position.cast<double>() - predicted;
      const double chi2 =
          offset.dot((covariance + corner.covariance.cast<double>()).inverse() * offset);
      if (chi2 > gate_chi2) {
        continue;
      }
      if (chi2 < found.chi2) {
        found.second_chi2 = found.chi2;
        found.chi2 = chi2;
        found.index = *it;
      } else {
        found.second_chi2 = std::min(found.second_chi2, chi2);
      }
    }
    return found;
  }

 private:
  const std::vector<ImageCorner>& corners_;
  std::vector<int> order_;
  double max_variance_px2_ = 0.0;
};

}  // namespace

std::vector<CornerMatch> matchCorners(const std::vector<ImageCorner>& image,
                                      const std::vector<VisibleCorner>& model,
                                      const PoseWithCovariance& T_world_camera,
                                      const PinholeCamera& camera,
                                      const CornerMatchingOptions& options) {
  const CornersByColumn by_column(image);
  const Eigen::Matrix2d floor =
      options.model_sigma_floor_px * options.model_sigma_floor_px * Eigen::Matrix2d::Identity();
  std::vector<CornerMatch> best;
  for (size_t m = 0; m < model.size(); ++m) {
    const Eigen::Vector3d p_camera = T_world_camera.pose.linear().transpose() *
                                     (model[m].p_world - T_world_camera.pose.translation());
    if (p_camera.z() <= 0.0) {
      continue;
    }
    const ProjectedPoint projected = projectPoint(model[m].p_world, T_world_camera, camera);
    const auto nearest =
        by_column.nearest(projected.pixel, projected.covariance + floor, options.gate_chi2);
    if (nearest.index >= 0 && nearest.second_chi2 - nearest.chi2 >= options.ambiguity_margin_chi2) {
      best.push_back({nearest.index, static_cast<int>(m), nearest.chi2});
    }
  }
  std::vector<CornerMatch> matches;
  for (const CornerMatch& match : best) {
    const bool shared = std::count_if(best.begin(), best.end(), [&](const CornerMatch& other) {
                          return other.image_index == match.image_index;
                        }) > 1;
    if (!shared) {
      matches.push_back(match);
    }
  }
  return matches;
}

}  // namespace lineloc
