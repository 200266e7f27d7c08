#include "robot/vision/edges/edge_linker.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace lineloc {
namespace {

struct Step {
  int dx, dy;
  float inverse_length;
};
constexpr float kInverseSqrt2 = 0.70710678f;
constexpr Step kSteps[8] = {{1, 0, 1.0f},           {-1, 0, 1.0f},          {0, 1, 1.0f},
                            {0, -1, 1.0f},          {1, 1, kInverseSqrt2},  {1, -1, kInverseSqrt2},
                            {-1, 1, kInverseSqrt2}, {-1, -1, kInverseSqrt2}};

Eigen::Vector2f tangentOf(const EdgePoint& point) {
  return {-point.normal.y(), point.normal.x()};
}

}  // namespace

EdgeLinker::EdgeLinker(const EdgeLinkerOptions& options)
    : options_(options), cos_max_turn_(static_cast<float>(std::cos(options.max_turn_rad))) {
  if (!(options.max_turn_rad > 0.0 && options.max_turn_rad < M_PI) || options.min_points < 2) {
    throw std::invalid_argument("edge linker: max_turn_rad must be in (0, pi), min_points >= 2");
  }
}

void EdgeLinker::link(const std::vector<EdgePoint>& points, const cv::Mat& point_index) {
  points_ = &points;
  point_index_ = &point_index;
  visited_.assign(points.size(), 0);
  chain_points_.clear();
  chains_.clear();
  for (int32_t seed = 0; seed < static_cast<int32_t>(points.size()); ++seed) {
    if (visited_[seed]) {
      continue;
    }
    visited_[seed] = 1;
    backward_.clear();
    walk(seed, -1.0f, backward_);
    const int begin = static_cast<int>(chain_points_.size());
    chain_points_.insert(chain_points_.end(), backward_.rbegin(), backward_.rend());
    chain_points_.push_back(seed);
    walk(seed, 1.0f, chain_points_);
    const PointRange chain{begin, static_cast<int>(chain_points_.size())};
    if (chain.size() >= options_.min_points) {
      chains_.push_back(chain);
    } else {
      chain_points_.resize(begin);
    }
  }
}

void EdgeLinker::walk(int32_t start, float direction_sign, std::vector<int32_t>& out) {
  const std::vector<EdgePoint>& points = *points_;
  int32_t current = start;
  Eigen::Vector2f direction = direction_sign * tangentOf(points[current]);
  for (;;) {
    const EdgePoint& here = points[current];
    const int x = here.pixel_x;
    const int y = here.pixel_y;
    int32_t best = -1;
    float best_alignment = 0.0f;
    Step best_step{0, 0, 0.0f};
    for (const Step& step : kSteps) {
      const int32_t candidate = point_index_->at<int32_t>(y + step.dy, x + step.dx);
      if (candidate < 0 || visited_[candidate]) {
        continue;
      }
      const float alignment =
          (step.dx * direction.x() + step.dy * direction.y()) * step.inverse_length;
      if (alignment <= best_alignment ||
          points[candidate].normal.dot(here.normal) < cos_max_turn_) {
        continue;
      }
      best = candidate;
      best_alignment = alignment;
      best_step = step;
    }
    if (best < 0) {
      return;
    }
    visited_[best] = 1;
    out.push_back(best);
    const Eigen::Vector2f tangent = tangentOf(points[best]);
    direction =
        (tangent.x() * best_step.dx + tangent.y() * best_step.dy >= 0.0f) ? tangent : -tangent;
    current = best;
  }
}

}  // namespace lineloc
