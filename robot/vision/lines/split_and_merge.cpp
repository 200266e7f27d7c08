#include "robot/vision/lines/split_and_merge.h"

#include <cmath>
#include <stdexcept>

#include "robot/vision/lines/line_moments.h"

namespace lineloc {
namespace {

struct Farthest {
  int index;
  float distance;
};

// The point of [begin, end) farthest from the chord points[begin] -> points[end - 1].
Farthest farthestFromChord(std::span<const Eigen::Vector2f> points, PointRange range) {
  const Eigen::Vector2f a = points[range.begin];
  const Eigen::Vector2f chord = points[range.end - 1] - a;
  const float length = chord.norm();
  Farthest farthest{range.begin, 0.0f};
  for (int i = range.begin + 1; i < range.end - 1; ++i) {
    const Eigen::Vector2f v = points[i] - a;
    const float distance =
        length > 0.0f ? std::abs(chord.x() * v.y() - chord.y() * v.x()) / length : v.norm();
    if (distance > farthest.distance) {
      farthest = {i, distance};
    }
  }
  return farthest;
}

}  // namespace

SplitAndMerge::SplitAndMerge(double split_distance_px, int min_points)
    : split_distance_px_(split_distance_px), min_points_(min_points) {
  if (!(split_distance_px > 0.0) || min_points < 3) {
    throw std::invalid_argument("split and merge: split_distance_px > 0, min_points >= 3");
  }
}

void SplitAndMerge::approximate(std::span<const Eigen::Vector2f> points,
                                std::vector<PointRange>& pieces) {
  cumulativeMoments(points, prefix_);
  approximate(points, prefix_, pieces);
}

void SplitAndMerge::approximate(std::span<const Eigen::Vector2f> points,
                                std::span<const PointMoments> prefix,
                                std::vector<PointRange>& pieces) {
  pieces_.clear();
  split(points);
  merge(points, prefix);
  for (const PointRange& piece : pieces_) {
    if (piece.size() >= min_points_) {
      pieces.push_back(piece);
    }
  }
}

void SplitAndMerge::split(std::span<const Eigen::Vector2f> points) {
  stack_.clear();
  stack_.push_back({0, static_cast<int>(points.size())});
  while (!stack_.empty()) {
    const PointRange range = stack_.back();
    stack_.pop_back();
    const Farthest farthest =
        range.size() >= 3 ? farthestFromChord(points, range) : Farthest{range.begin, 0.0f};
    if (farthest.distance <= split_distance_px_) {
      pieces_.push_back(range);
      continue;
    }
    stack_.push_back({farthest.index + 1, range.end});
    stack_.push_back({range.begin, farthest.index});
  }
}

void SplitAndMerge::merge(std::span<const Eigen::Vector2f> points,
                          std::span<const PointMoments> prefix) {
  size_t i = 0;
  while (i + 1 < pieces_.size()) {
    const PointRange joined{pieces_[i].begin, pieces_[i + 1].end};
    if (fitsOneLine(points, prefix, joined)) {
      pieces_[i] = joined;
      pieces_.erase(pieces_.begin() + static_cast<std::ptrdiff_t>(i) + 1);
    } else {
      ++i;
    }
  }
}

bool SplitAndMerge::fitsOneLine(std::span<const Eigen::Vector2f> points,
                                std::span<const PointMoments> prefix, PointRange range) const {
  const LineFit fit = fitLine(prefix[range.end] - prefix[range.begin], LineFitOptions{});
  if (fit.status != LineFitStatus::kOk) {
    return false;
  }
  for (int i = range.begin; i < range.end; ++i) {
    if (std::abs(fit.distance(points[i].cast<double>())) > split_distance_px_) {
      return false;
    }
  }
  return true;
}

}  // namespace lineloc
