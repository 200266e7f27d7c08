#include "backbone/enrichment/surface_line_tracks.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <iterator>
#include <set>
#include <string>

namespace lineloc {
namespace {

double gateOf(const SurfaceSegment& segment, const SurfaceLineTrackOptions& options) {
  return std::max(options.min_gate_m, options.gate_sigma * segment.placement_sigma_m);
}

}  // namespace

SurfaceLineTracks::SurfaceLineTracks(const SurfaceLineTrackOptions& options) : options_(options) {}

double SurfaceLineTracks::distanceInGate(const Track& track, const SurfaceSegment& segment) const {
  if (track.plane.normal.dot(segment.plane.normal) < std::cos(options_.plane_angle_rad) ||
      std::abs(track.plane.offset - segment.plane.offset) > options_.plane_offset_m) {
    return -1.0;
  }
  const Eigen::Vector3d direction = (segment.end_world - segment.start_world).normalized();
  if (track.direction.cross(direction).norm() > std::sin(options_.max_angle_rad)) {
    return -1.0;
  }
  if (!segment.brighter_side.isZero() && !track.brighter_side.isZero() &&
      segment.brighter_side.dot(track.brighter_side) <= 0.0) {
    return -1.0;
  }
  const auto across = [&](const Eigen::Vector3d& point) {
    const Eigen::Vector3d offset = point - track.point;
    return (offset - offset.dot(track.direction) * track.direction).norm();
  };
  const double distance = std::max(across(segment.start_world), across(segment.end_world));
  if (distance > gateOf(segment, options_)) {
    return -1.0;
  }
  const double s0 = track.direction.dot(segment.start_world - track.point);
  const double s1 = track.direction.dot(segment.end_world - track.point);
  if (std::max(s0, s1) < track.along_min - options_.max_gap_m ||
      std::min(s0, s1) > track.along_max + options_.max_gap_m) {
    return -1.0;
  }
  return distance;
}

void SurfaceLineTracks::fit(Track& track) {
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (const SurfaceSegment& view : track.views) {
    mean += view.start_world + view.end_world;
  }
  mean /= 2.0 * static_cast<double>(track.views.size());
  Eigen::Matrix3d scatter = Eigen::Matrix3d::Zero();
  for (const SurfaceSegment& view : track.views) {
    for (const Eigen::Vector3d& point : {view.start_world, view.end_world}) {
      scatter += (point - mean) * (point - mean).transpose();
    }
  }
  // The principal axis, kept in the plane.
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(scatter);
  Eigen::Vector3d direction = eigen.eigenvectors().col(2);
  direction -= direction.dot(track.plane.normal) * track.plane.normal;
  track.direction = direction.normalized();
  track.point = mean - (track.plane.normal.dot(mean) - track.plane.offset) * track.plane.normal;
  track.along_min = std::numeric_limits<double>::infinity();
  track.along_max = -track.along_min;
  for (const SurfaceSegment& view : track.views) {
    for (const Eigen::Vector3d& point : {view.start_world, view.end_world}) {
      const double along = track.direction.dot(point - track.point);
      track.along_min = std::min(track.along_min, along);
      track.along_max = std::max(track.along_max, along);
    }
  }
}

void SurfaceLineTracks::add(const SurfaceSegment& segment) {
  std::vector<Track>& tracks = tracks_by_building_[segment.building_id];
  Track* nearest = nullptr;
  double nearest_m = 0.0;
  for (Track& track : tracks) {
    const double distance = distanceInGate(track, segment);
    if (distance >= 0.0 && (nearest == nullptr || distance < nearest_m)) {
      nearest = &track;
      nearest_m = distance;
    }
  }
  if (nearest == nullptr) {
    Track& track = tracks.emplace_back();
    track.building_id = segment.building_id;
    track.plane = segment.plane;
    track.brighter_side = segment.brighter_side;
    track.first_stamp_ns = segment.stamp_ns;
    nearest = &track;
  }
  Track& track = *nearest;
  if (static_cast<int>(track.views.size()) < options_.max_views) {
    track.views.push_back(segment);
  } else {
    track.views.back() = segment;
  }
  if (track.brighter_side.isZero()) {
    track.brighter_side = segment.brighter_side;
  }
  ++track.views_seen;
  track.first_stamp_ns = std::min(track.first_stamp_ns, segment.stamp_ns);
  track.last_stamp_ns = std::max(track.last_stamp_ns, segment.stamp_ns);
  fit(track);
}

bool SurfaceLineTracks::offPlane(const std::vector<LineObservation>& views,
                                 const Plane& plane) const {
  const LineTriangulation free = triangulateLine(views, options_.triangulation);
  if (!free.line) {
    return false;  // the views alone do not fix it: nothing to refute the plane with
  }
  const auto beyond = [&](const Eigen::Vector3d& point, const Eigen::Matrix3d& covariance) {
    const double variance = plane.normal.dot(covariance * plane.normal);
    if (variance > options_.max_plane_test_sigma_m * options_.max_plane_test_sigma_m) {
      return false;
    }
    const double offset = plane.normal.dot(point) - plane.offset;
    return offset * offset > options_.off_plane_sigma * options_.off_plane_sigma * variance;
  };
  return beyond(free.line->start_world, free.line->start_covariance) ||
         beyond(free.line->end_world, free.line->end_covariance);
}

std::vector<LineCandidate> SurfaceLineTracks::candidates() const {
  std::vector<LineCandidate> candidates;
  for (const auto& [building_id, tracks] : tracks_by_building_) {
    for (const Track& track : tracks) {
      if (static_cast<int>(track.views.size()) < options_.triangulation.min_views) {
        continue;
      }
      std::vector<LineObservation> views;
      std::set<std::string> robots;
      for (const SurfaceSegment& view : track.views) {
        views.push_back(view.view);
        robots.insert(view.robot_id);
      }
      LineTriangulation triangulated = triangulateLine(views, options_.triangulation, track.plane);
      if (!triangulated.line || offPlane(views, track.plane)) {
        continue;
      }
      candidates.push_back({std::move(*triangulated.line), building_id, track.plane,
                            track.brighter_side, track.views_seen, static_cast<int>(robots.size()),
                            track.first_stamp_ns, track.last_stamp_ns});
    }
  }
  return candidates;
}

void SurfaceLineTracks::forgetStale(int64_t before_ns) {
  for (auto building = tracks_by_building_.begin(); building != tracks_by_building_.end();) {
    std::erase_if(building->second, [&](const Track& track) {
      return static_cast<int>(track.views.size()) < options_.triangulation.min_views &&
             track.last_stamp_ns < before_ns;
    });
    building = building->second.empty() ? tracks_by_building_.erase(building) : std::next(building);
  }
}

size_t SurfaceLineTracks::viewCount() const {
  size_t count = 0;
  for (const auto& [building_id, tracks] : tracks_by_building_) {
    for (const Track& track : tracks) {
      count += track.views.size();
    }
  }
  return count;
}

size_t SurfaceLineTracks::trackCount() const {
  size_t count = 0;
  for (const auto& [building_id, tracks] : tracks_by_building_) {
    count += tracks.size();
  }
  return count;
}

}  // namespace lineloc
