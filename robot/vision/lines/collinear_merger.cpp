#include "robot/vision/lines/collinear_merger.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <stdexcept>

namespace lineloc {

CollinearMerger::CollinearMerger(const CollinearMergeOptions& options) : options_(options) {
  if (!(options.max_angle_rad >= 0.0) || !(options.max_distance_px >= 0.0) ||
      !(options.max_gap_px >= 0.0) || !(options.max_gap_ratio >= 0.0)) {
    throw std::invalid_argument("collinear merge: tolerances must be non-negative");
  }
}

// Most pairs in an angle window lie on other lines: that test goes first, as
// it almost always fails the same way.
bool CollinearMerger::joinable(const Extent& a, const Extent& b) const {
  const double d = options_.max_distance_px;
  const auto off = [d](const Extent& line, const Eigen::Vector2d& p) {
    return std::abs(line.normal.dot(p - line.centroid)) > d;
  };
  if (off(a, b.start) || off(a, b.end) || off(b, a.start) || off(b, a.end) ||
      a.gradient_sum.dot(b.gradient_sum) <= 0.0) {
    return false;
  }
  const double b0 = a.direction.dot(b.start - a.centroid);
  const double b1 = a.direction.dot(b.end - a.centroid);
  const double gap = std::max(std::min(b0, b1) - a.end_along, a.start_along - std::max(b0, b1));
  const double shorter = std::min(a.end_along - a.start_along, b.end_along - b.start_along);
  return gap <= std::min(options_.max_gap_px, options_.max_gap_ratio * shorter);
}

int32_t CollinearMerger::root(int32_t i) {
  while (parent_[i] != i) {
    parent_[i] = parent_[parent_[i]];
    i = parent_[i];
  }
  return i;
}

// Pairs within max_angle of each other by a sweep over the segments sorted
// by angle (wrapping at pi), compact copies in that order.
void CollinearMerger::findGroups(const std::vector<LineSegment>& segments) {
  const int32_t count = static_cast<int32_t>(segments.size());
  by_angle_.resize(count);
  for (int32_t i = 0; i < count; ++i) {
    const LineSegment& s = segments[i];
    by_angle_[i] = {std::atan2(s.fit.direction.y(), s.fit.direction.x()),
                    s.fit.centroid,
                    s.fit.direction,
                    s.fit.normal,
                    s.start(),
                    s.end(),
                    s.gradient_sum,
                    s.start_along,
                    s.end_along,
                    i};
  }
  std::sort(by_angle_.begin(), by_angle_.end(),
            [](const Extent& a, const Extent& b) { return a.angle < b.angle; });
  parent_.resize(count);
  std::iota(parent_.begin(), parent_.end(), 0);
  for (int32_t k = 0; k < count; ++k) {
    const Extent& a = by_angle_[k];
    for (int32_t step = 1; step < count; ++step) {
      const Extent& b = by_angle_[(k + step) % count];
      const double wrap = (k + step >= count) ? M_PI : 0.0;
      if (b.angle + wrap - a.angle > options_.max_angle_rad) {
        break;
      }
      if (joinable(a, b)) {
        parent_[root(b.segment)] = root(a.segment);
      }
    }
  }
}

void CollinearMerger::merge(std::vector<LineSegment>& segments, const LineFitOptions& fit_options) {
  findGroups(segments);
  originals_.assign(segments.begin(), segments.end());
  const int32_t count = static_cast<int32_t>(segments.size());
  for (int32_t i = 0; i < count; ++i) {
    const int32_t r = root(i);
    if (r == i) {
      continue;
    }
    segments[r].moments += originals_[i].moments;
    segments[r].gradient_sum += originals_[i].gradient_sum;
    segments[r].step_sum += originals_[i].step_sum;
  }
  // A root that absorbed others has more points than any of its members.
  for (int32_t i = 0; i < count; ++i) {
    if (root(i) == i && segments[i].moments.n != originals_[i].moments.n) {
      segments[i].fit = fitLine(segments[i].moments, fit_options);
      segments[i].start_along = std::numeric_limits<double>::max();
      segments[i].end_along = std::numeric_limits<double>::lowest();
    }
  }
  for (int32_t i = 0; i < count; ++i) {
    LineSegment& group = segments[root(i)];
    if (group.moments.n == originals_[i].moments.n) {
      continue;
    }
    for (const Eigen::Vector2d& p : {originals_[i].start(), originals_[i].end()}) {
      group.start_along = std::min(group.start_along, group.fit.along(p));
      group.end_along = std::max(group.end_along, group.fit.along(p));
    }
  }
  int32_t kept = 0;
  for (int32_t i = 0; i < count; ++i) {
    if (root(i) == i) {
      segments[kept++] = segments[i];
    }
  }
  segments.resize(kept);
}

}  // namespace lineloc
