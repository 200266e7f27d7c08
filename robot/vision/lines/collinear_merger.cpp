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

bool CollinearMerger::joinable(const LineSegment& a, const LineSegment& b) const {
  if (a.gradient_sum.dot(b.gradient_sum) <= 0.0) {
    return false;
  }
  const double d = options_.max_distance_px;
  if (std::abs(a.fit.distance(b.start())) > d || std::abs(a.fit.distance(b.end())) > d ||
      std::abs(b.fit.distance(a.start())) > d || std::abs(b.fit.distance(a.end())) > d) {
    return false;
  }
  const double b0 = a.fit.along(b.start());
  const double b1 = a.fit.along(b.end());
  const double gap = std::max(std::min(b0, b1) - a.end_along, a.start_along - std::max(b0, b1));
  const double shorter = std::min(a.length(), b.length());
  return gap <= std::min(options_.max_gap_px, options_.max_gap_ratio * shorter);
}

int32_t CollinearMerger::root(int32_t i) {
  while (parent_[i] != i) {
    parent_[i] = parent_[parent_[i]];
    i = parent_[i];
  }
  return i;
}

void CollinearMerger::findGroups(const std::vector<LineSegment>& segments) {
  const int32_t count = static_cast<int32_t>(segments.size());
  angle_.resize(count);
  for (int32_t i = 0; i < count; ++i) {
    angle_[i] = std::atan2(segments[i].fit.direction.y(), segments[i].fit.direction.x());
  }
  order_.resize(count);
  std::iota(order_.begin(), order_.end(), 0);
  std::sort(order_.begin(), order_.end(),
            [&](int32_t a, int32_t b) { return angle_[a] < angle_[b]; });
  parent_.resize(count);
  std::iota(parent_.begin(), parent_.end(), 0);
  for (int32_t k = 0; k < count; ++k) {
    const int32_t i = order_[k];
    for (int32_t step = 1; step < count; ++step) {
      const int32_t j = order_[(k + step) % count];
      const double wrap = (k + step >= count) ? M_PI : 0.0;
      if (angle_[j] + wrap - angle_[i] > options_.max_angle_rad) {
        break;
      }
      if (joinable(segments[i], segments[j])) {
        parent_[root(j)] = root(i);
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
