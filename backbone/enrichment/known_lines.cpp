#include "backbone/enrichment/known_lines.h"

#include <algorithm>

namespace lineloc {
namespace {

bool sameLine(const TriangulatedLine& line, const ModelSegment& model,
              const KnownLineOptions& options) {
  const Eigen::Vector3d along = model.end_world - model.start_world;
  const double length = along.norm();
  if (length < 1e-9) {
    return false;
  }
  const Eigen::Vector3d direction = along / length;
  if (direction.cross(line.direction).norm() > std::sin(options.max_angle_rad)) {
    return false;
  }
  const auto across = [&](const Eigen::Vector3d& point) {
    const Eigen::Vector3d offset = point - model.start_world;
    return (offset - offset.dot(direction) * direction).norm();
  };
  if (across(line.start_world) > options.max_distance_m ||
      across(line.end_world) > options.max_distance_m) {
    return false;
  }
  const double s0 = direction.dot(line.start_world - model.start_world);
  const double s1 = direction.dot(line.end_world - model.start_world);
  return std::max(s0, s1) > 0.0 && std::min(s0, s1) < length;
}

}  // namespace

std::vector<LineCandidate> withoutModelLines(const std::vector<LineCandidate>& candidates,
                                             const std::vector<ModelSegment>& model_lines,
                                             const KnownLineOptions& options) {
  std::vector<LineCandidate> unknown;
  for (const LineCandidate& candidate : candidates) {
    if (std::none_of(model_lines.begin(), model_lines.end(), [&](const ModelSegment& model) {
          return sameLine(candidate.line, model, options);
        })) {
      unknown.push_back(candidate);
    }
  }
  return unknown;
}

}  // namespace lineloc
