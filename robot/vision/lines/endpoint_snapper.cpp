#include "robot/vision/lines/endpoint_snapper.h"

#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace lineloc {
namespace {

double cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return a.x() * b.y() - a.y() * b.x();
}

void moveEndpoint(LineSegment& segment, bool is_start, double along, double sigma_along_px) {
  if (is_start) {
    segment.start_along = along;
    segment.start_sigma_along_px = sigma_along_px;
  } else {
    segment.end_along = along;
    segment.end_sigma_along_px = sigma_along_px;
  }
}

}  // namespace

EndpointSnapper::EndpointSnapper(const EndpointSnapOptions& options)
    : options_(options), min_sin_angle_(std::sin(options.min_angle_rad)) {
  if (!(options.radius_px >= 0.0) ||
      !(options.min_angle_rad > 0.0 && options.min_angle_rad <= M_PI / 2)) {
    throw std::invalid_argument("endpoint snap: radius_px >= 0, min_angle_rad in (0, pi/2]");
  }
}

void EndpointSnapper::snap(std::vector<LineSegment>& segments) {
  endpoints_.clear();
  candidates_.clear();
  junctions_.clear();
  for (int32_t i = 0; i < static_cast<int32_t>(segments.size()); ++i) {
    endpoints_.push_back({segments[i].start(), i, true, false});
    endpoints_.push_back({segments[i].end(), i, false, false});
  }
  std::sort(endpoints_.begin(), endpoints_.end(),
            [](const Endpoint& a, const Endpoint& b) { return a.position.x() < b.position.x(); });
  const double window_px = 2.0 * options_.radius_px;
  const auto count = static_cast<int32_t>(endpoints_.size());
  for (int32_t i = 0; i < count; ++i) {
    for (int32_t j = i + 1;
         j < count && endpoints_[j].position.x() - endpoints_[i].position.x() <= window_px; ++j) {
      if (std::abs(endpoints_[j].position.y() - endpoints_[i].position.y()) <= window_px) {
        addCandidate(segments, i, j);
      }
    }
  }
  std::sort(candidates_.begin(), candidates_.end(),
            [](const Candidate& a, const Candidate& b) { return a.distance_px < b.distance_px; });
  for (const Candidate& candidate : candidates_) {
    if (!endpoints_[candidate.a].snapped && !endpoints_[candidate.b].snapped) {
      apply(segments, candidate);
    }
  }
}

void EndpointSnapper::addCandidate(const std::vector<LineSegment>& segments, int32_t a, int32_t b) {
  const Endpoint& end_a = endpoints_[a];
  const Endpoint& end_b = endpoints_[b];
  if (end_a.segment == end_b.segment) {
    return;
  }
  const LineSegment& line_a = segments[end_a.segment];
  const LineSegment& line_b = segments[end_b.segment];
  const double sin_angle = cross(line_a.fit.direction, line_b.fit.direction);
  if (std::abs(sin_angle) < min_sin_angle_) {
    return;
  }
  // c_a + s d_a = c_b + u d_b.
  const Eigen::Vector2d offset = line_b.fit.centroid - line_a.fit.centroid;
  const double s = cross(offset, line_b.fit.direction) / sin_angle;
  const double u = cross(offset, line_a.fit.direction) / sin_angle;
  const Eigen::Vector2d x = line_a.fit.centroid + s * line_a.fit.direction;
  const double distance_px = std::max((x - end_a.position).norm(), (x - end_b.position).norm());
  if (distance_px > options_.radius_px) {
    return;
  }
  const double new_length_a = end_a.is_start ? line_a.end_along - s : s - line_a.start_along;
  const double new_length_b = end_b.is_start ? line_b.end_along - u : u - line_b.start_along;
  if (new_length_a > 0.0 && new_length_b > 0.0) {
    candidates_.push_back({a, b, s, u, distance_px});
  }
}

void EndpointSnapper::apply(std::vector<LineSegment>& segments, const Candidate& candidate) {
  Endpoint& a = endpoints_[candidate.a];
  Endpoint& b = endpoints_[candidate.b];
  LineSegment& line_a = segments[a.segment];
  LineSegment& line_b = segments[b.segment];
  const double s = candidate.s;
  const double u = candidate.u;
  const double sin_angle = cross(line_a.fit.direction, line_b.fit.direction);
  moveEndpoint(line_a, a.is_start, s,
               std::sqrt(line_b.fit.normalVariance(u)) / std::abs(sin_angle));
  moveEndpoint(line_b, b.is_start, u,
               std::sqrt(line_a.fit.normalVariance(s)) / std::abs(sin_angle));
  Eigen::Matrix2d normals;
  normals << line_a.fit.normal.transpose(), line_b.fit.normal.transpose();
  const Eigen::Matrix2d inverse = normals.inverse();
  const Eigen::Vector2d normal_variance(line_a.fit.normalVariance(s), line_b.fit.normalVariance(u));
  const Eigen::Vector2d x = line_a.fit.centroid + s * line_a.fit.direction;
  junctions_.push_back({x, inverse * normal_variance.asDiagonal() * inverse.transpose()});
  a.snapped = true;
  b.snapped = true;
}

}  // namespace lineloc
