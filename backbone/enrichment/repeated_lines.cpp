#include "backbone/enrichment/repeated_lines.h"

#include <algorithm>

namespace lineloc {
namespace {

// Whether b repeats a (see the header).
bool repeats(const LineCandidate& a, const LineCandidate& b, const RepeatedLineOptions& options) {
  if (a.building_id != b.building_id ||
      a.plane.normal.dot(b.plane.normal) < std::cos(options.max_angle_rad) ||
      a.line.direction.cross(b.line.direction).norm() > std::sin(options.max_angle_rad) ||
      a.brighter_side.dot(b.brighter_side) <= 0.0) {
    return false;
  }
  const Eigen::Vector3d& direction = a.line.direction;
  const Eigen::Vector3d middle = 0.5 * (b.line.start_world + b.line.end_world);
  const Eigen::Vector3d offset = middle - a.line.start_world;
  if ((offset - offset.dot(direction) * direction).norm() >= options.min_separation_m) {
    return false;
  }
  const double a1 = direction.dot(a.line.end_world - a.line.start_world);
  const double b0 = direction.dot(b.line.start_world - a.line.start_world);
  const double b1 = direction.dot(b.line.end_world - a.line.start_world);
  return std::max(b0, b1) > std::min(0.0, a1) && std::min(b0, b1) < std::max(0.0, a1);
}

}  // namespace

std::vector<LineCandidate> withoutRepeatedLines(const std::vector<LineCandidate>& candidates,
                                                const RepeatedLineOptions& options) {
  std::vector<LineCandidate> distinct;
  for (size_t i = 0; i < candidates.size(); ++i) {
    bool repeated = false;
    for (size_t j = 0; j < candidates.size() && !repeated; ++j) {
      repeated = j != i && repeats(candidates[i], candidates[j], options);
    }
    if (!repeated) {
      distinct.push_back(candidates[i]);
    }
  }
  return distinct;
}

}  // namespace lineloc
