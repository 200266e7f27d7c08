#include "segment_precision_recall.h"

#include <algorithm>
#include <cmath>
#include <optional>

namespace lineloc::testing {
namespace {

// Liang-Barsky: the part of s inside the box, if any.
std::optional<Segment2d> clipped(const Segment2d& s, const Eigen::AlignedBox2d& box) {
  const Eigen::Vector2d d = s.end - s.start;
  double t0 = 0.0, t1 = 1.0;
  for (int axis = 0; axis < 2; ++axis) {
    for (const auto& [p, q] : {std::pair{-d[axis], s.start[axis] - box.min()[axis]},
                               std::pair{d[axis], box.max()[axis] - s.start[axis]}}) {
      if (p == 0.0) {
        if (q < 0.0) {
          return std::nullopt;
        }
        continue;
      }
      const double t = q / p;
      if (p < 0.0) {
        t0 = std::max(t0, t);
      } else {
        t1 = std::min(t1, t);
      }
    }
  }
  if (t0 > t1) {
    return std::nullopt;
  }
  return Segment2d{s.start + t0 * d, s.start + t1 * d};
}

std::vector<Segment2d> prepared(const std::vector<Segment2d>& segments,
                                const Eigen::AlignedBox2d& region, double min_length_px) {
  std::vector<Segment2d> kept;
  for (const Segment2d& segment : segments) {
    const std::optional<Segment2d> inside = clipped(segment, region);
    const double length = inside ? (inside->end - inside->start).norm() : 0.0;
    if (length > 0.0 && length >= min_length_px) {
      kept.push_back(*inside);
    }
  }
  return kept;
}

double distanceToSegment(const Eigen::Vector2d& p, const Segment2d& s) {
  const Eigen::Vector2d d = s.end - s.start;
  const double t = std::clamp((p - s.start).dot(d) / d.squaredNorm(), 0.0, 1.0);
  return (s.start + t * d - p).norm();
}

// Length of `segments` whose samples lie near one of `others` at a small angle.
double coveredLength(const std::vector<Segment2d>& segments, const std::vector<Segment2d>& others,
                     const CoverageOptions& options, double& total_length) {
  const double min_cosine = std::cos(options.max_angle_deg * M_PI / 180.0);
  double covered = 0.0;
  total_length = 0.0;
  for (const Segment2d& segment : segments) {
    const Eigen::Vector2d d = segment.end - segment.start;
    const double length = d.norm();
    const Eigen::Vector2d u = d / length;
    const int samples = std::max(1, static_cast<int>(std::round(length / options.sample_step_px)));
    int near = 0;
    for (int i = 0; i < samples; ++i) {
      const Eigen::Vector2d p = segment.start + ((i + 0.5) / samples) * d;
      near += std::any_of(others.begin(), others.end(), [&](const Segment2d& other) {
        const Eigen::Vector2d v = (other.end - other.start).normalized();
        return std::abs(u.dot(v)) >= min_cosine &&
               distanceToSegment(p, other) <= options.max_distance_px;
      });
    }
    covered += length * near / samples;
    total_length += length;
  }
  return covered;
}

// The larger of the distances between the endpoints of a and b, paired the
// closer way.
double endpointDistance(const Segment2d& a, const Segment2d& b) {
  const double same = std::max((a.start - b.start).norm(), (a.end - b.end).norm());
  const double swapped = std::max((a.start - b.end).norm(), (a.end - b.start).norm());
  return std::min(same, swapped);
}

}  // namespace

CoverageScore scoreCoverage(const std::vector<Segment2d>& labelled,
                            const std::vector<Segment2d>& detected,
                            const Eigen::AlignedBox2d& region, const CoverageOptions& options) {
  const std::vector<Segment2d> truth = prepared(labelled, region, options.min_length_px);
  const std::vector<Segment2d> found = prepared(detected, region, options.min_length_px);
  CoverageScore score;
  score.labelled_segments = static_cast<int>(truth.size());
  score.detected_segments = static_cast<int>(found.size());
  const double recalled = coveredLength(truth, found, options, score.labelled_length_px);
  const double correct = coveredLength(found, truth, options, score.detected_length_px);
  score.recall = score.labelled_length_px > 0.0 ? recalled / score.labelled_length_px : 0.0;
  score.precision = score.detected_length_px > 0.0 ? correct / score.detected_length_px : 0.0;
  return score;
}

EndpointScore scoreEndpoints(const std::vector<Segment2d>& labelled,
                             const std::vector<Segment2d>& detected,
                             const Eigen::AlignedBox2d& region, const EndpointOptions& options) {
  const std::vector<Segment2d> truth = prepared(labelled, region, options.min_length_px);
  const std::vector<Segment2d> found = prepared(detected, region, options.min_length_px);
  struct Candidate {
    double distance;
    size_t truth, found;
  };
  std::vector<Candidate> candidates;
  for (size_t t = 0; t < truth.size(); ++t) {
    for (size_t f = 0; f < found.size(); ++f) {
      const double distance = endpointDistance(truth[t], found[f]);
      if (distance <= options.max_endpoint_distance_px) {
        candidates.push_back({distance, t, f});
      }
    }
  }
  std::sort(candidates.begin(), candidates.end(),
            [](const Candidate& a, const Candidate& b) { return a.distance < b.distance; });
  std::vector<bool> truth_used(truth.size()), found_used(found.size());
  EndpointScore score;
  for (const Candidate& c : candidates) {
    if (!truth_used[c.truth] && !found_used[c.found]) {
      truth_used[c.truth] = found_used[c.found] = true;
      ++score.matched;
    }
  }
  score.labelled_segments = static_cast<int>(truth.size());
  score.detected_segments = static_cast<int>(found.size());
  score.recall = truth.empty() ? 0.0 : double(score.matched) / truth.size();
  score.precision = found.empty() ? 0.0 : double(score.matched) / found.size();
  return score;
}

}  // namespace lineloc::testing
