#include "segment_scoring.h"

#include <algorithm>
#include <cmath>

namespace lineloc::testing {
namespace {

struct Placement {
  bool on_line;
  double coverage;  // fraction of the true length covered
  double angle_error_deg;
};

double angleBetweenDeg(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  const double cosine = std::abs(a.normalized().dot(b.normalized()));
  return std::acos(std::min(1.0, cosine)) * 180.0 / M_PI;
}

Placement place(const SceneSegment& truth, const ImageSegment& detected,
                const ScoringOptions& options) {
  const Eigen::Vector2d d = truth.end - truth.start;
  const double length = d.norm();
  const Eigen::Vector2d u = d / length;
  const Eigen::Vector2d n(-u.y(), u.x());
  const Eigen::Vector2d a = detected.start.cast<double>() - truth.start;
  const Eigen::Vector2d b = detected.end.cast<double>() - truth.start;
  const double ta = a.dot(u);
  const double tb = b.dot(u);
  const double slack = options.max_distance_px;
  const double angle = angleBetweenDeg(d, b - a);
  const bool on_line = std::abs(a.dot(n)) <= slack && std::abs(b.dot(n)) <= slack &&
                       std::min(ta, tb) >= -slack && std::max(ta, tb) <= length + slack &&
                       angle <= options.max_angle_deg;
  const double covered = std::min(length, std::max(ta, tb)) - std::max(0.0, std::min(ta, tb));
  return {on_line, std::max(0.0, covered) / length, angle};
}

double endpointError(const SceneSegment& truth, const Eigen::Vector2f& p) {
  const Eigen::Vector2d q = p.cast<double>();
  return std::min((q - truth.start).norm(), (q - truth.end).norm());
}

}  // namespace

SegmentScore scoreSegments(const SyntheticScene& scene, const std::vector<ImageSegment>& detected,
                           const ScoringOptions& options) {
  SegmentScore score;
  for (const ImageSegment& segment : detected) {
    if ((segment.end - segment.start).norm() < options.min_length_px) {
      continue;
    }
    ++score.detected;
    const bool on_some = std::any_of(
        scene.segments.begin(), scene.segments.end(),
        [&](const SceneSegment& truth) { return place(truth, segment, options).on_line; });
    score.spurious += on_some ? 0 : 1;
  }
  for (const SceneSegment& truth : scene.segments) {
    if ((truth.end - truth.start).norm() < options.min_length_px) {
      continue;
    }
    ++score.true_segments;
    const ImageSegment* best = nullptr;
    Placement best_placement{false, 0.0, 0.0};
    for (const ImageSegment& segment : detected) {
      const Placement placement = place(truth, segment, options);
      if (placement.on_line && placement.coverage > best_placement.coverage) {
        best = &segment;
        best_placement = placement;
      }
    }
    if (best == nullptr || best_placement.coverage < options.min_coverage) {
      continue;
    }
    ++score.found;
    for (const Eigen::Vector2f& p : {best->start, best->end}) {
      score.endpoint_errors_px.push_back(endpointError(truth, p));
      score.max_endpoint_error_px =
          std::max(score.max_endpoint_error_px, score.endpoint_errors_px.back());
    }
    score.angle_errors_deg.push_back(best_placement.angle_error_deg);
    score.max_angle_error_deg = std::max(score.max_angle_error_deg, best_placement.angle_error_deg);
  }
  return score;
}

CornerScore scoreCorners(const SyntheticScene& scene, const std::vector<ImageCorner>& detected,
                         double max_distance_px) {
  CornerScore score;
  for (const Eigen::Vector2d& truth : scene.corners) {
    ++score.true_corners;
    double nearest = max_distance_px;
    bool found = false;
    for (const ImageCorner& corner : detected) {
      const double distance = (corner.position.cast<double>() - truth).norm();
      if (distance <= nearest) {
        nearest = distance;
        found = true;
      }
    }
    if (found) {
      ++score.found;
      score.errors_px.push_back(nearest);
      score.max_error_px = std::max(score.max_error_px, nearest);
    }
  }
  return score;
}

}  // namespace lineloc::testing
