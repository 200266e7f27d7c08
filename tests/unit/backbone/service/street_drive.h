// A robot driving north down the synthetic street of the matching tests
// (synthetic_street.h) from a DGPS + compass start, as the backbone receives
// it: its LineSets, its odometry and the street's map in memory, with no
// database and no DDS.
#pragma once

#include <cstdint>
#include <memory>
#include <random>
#include <utility>

#include "backbone/service/predicted_motion.h"
#include "backbone/service/prepared_maps.h"
#include "common/messages/messages.h"
#include "tests/unit/backbone/matching/synthetic_street.h"

namespace lineloc::testing {

// The street's map as the backbone prepares it, in memory.
inline std::shared_ptr<const PreparedMap> preparedMap(const Street& street) {
  auto tile = std::make_shared<MapTile>();
  for (const ModelSegment& edge : street.edges) {
    db::ModelLine line;
    line.id = edge.id;
    line.start_world = edge.start_world;
    line.end_world = edge.end_world;
    tile->lines.push_back(line);
  }
  for (size_t i = 0; i < street.faces.size(); ++i) {
    tile->faces.push_back(
        {static_cast<int64_t>(i), street.face_building_ids[i], 0, street.faces[i]});
  }
  return std::make_shared<PreparedMap>(tile, Eigen::Vector3d(0.0, 50.0, 0.0));
}

// A robot driving north from the synthetic street's true pose at 1.2 m/s,
// searched for every 0.3 s.
constexpr double kFramePeriodS = 0.3;
constexpr double kSpeedMS = 1.2;

inline Eigen::Isometry3d truthAt(int frame, double speed_m_s = kSpeedMS) {
  Eigen::Isometry3d pose = truePose().pose;
  pose.translation().y() += speed_m_s * kFramePeriodS * frame;
  return pose;
}

// The frame as the robot sends it: the visible model pieces with pixel noise
// and as many window frames again, which no model holds; its prediction, a
// DGPS + compass start 3 m and 0.3 degrees off.
inline LineSetData lineSetAt(const Street& street, const OcclusionScene& occlusion, int frame,
                             const Eigen::Isometry3d& T_world_camera, std::mt19937& random) {
  LineSetData line_set;
  line_set.robot_id = "session-test";
  line_set.sequence_number = static_cast<uint32_t>(frame);
  line_set.stamp_ns = static_cast<int64_t>(1e9 + frame * kFramePeriodS * 1e9);
  line_set.camera = kCamera;
  const PoseWithCovariance truth{T_world_camera, diagonalPoseCovariance(0.01, 0.001)};
  for (const VisibleSegment& seen : visibleSegments(street.edges, occlusion, truth, kCamera, {})) {
    const ProjectedSegment p = projectSegment(seen.start_world, seen.end_world, truth, kCamera);
    line_set.segments.push_back(observe(p.start_px, p.end_px, random));
  }
  std::uniform_real_distribution<double> u(40, 600), v(40, 440);
  const size_t modelled = line_set.segments.size();
  for (size_t i = 0; i < modelled; ++i) {
    const Eigen::Vector2d a(u(random), v(random));
    const Eigen::Vector2d b = a + (i % 2 == 0 ? Eigen::Vector2d(0, 30) : Eigen::Vector2d(30, 0));
    line_set.segments.push_back(observe(a, b, random));
  }
  PoseWithCovariance& predicted = line_set.predicted_T_world_camera;
  predicted.pose = T_world_camera;
  predicted.pose.translation() += Eigen::Vector3d(3.0, -2.0, 0.05);
  predicted.pose.linear() =
      Eigen::AngleAxisd(0.3 * M_PI / 180.0, Eigen::Vector3d::UnitZ()).toRotationMatrix() *
      predicted.pose.linear();
  predicted.covariance = diagonalPoseCovariance(4.0, 0.5 * M_PI / 180.0);
  predicted.covariance(2, 2) = 0.1 * 0.1;
  return line_set;
}

// Exact dead reckoning: the odometry frame is the world's.
inline OdometryPose odometryAt(const Eigen::Isometry3d& T_world_camera) {
  return {T_world_camera, 0};
}

// A street, its map, and the robot's frames on it.
class StreetDrive {
 public:
  StreetDrive(Street street, uint32_t seed)
      : street_(std::move(street)),
        occlusion_(street_.faces, street_.face_building_ids),
        map_(preparedMap(street_)),
        random_(seed) {}

  // The LineSet of `frame` of a drive at `speed_m_s`; its true pose in `truth`.
  LineSetData frame(int frame, double speed_m_s, Eigen::Isometry3d& truth) {
    truth = truthAt(frame, speed_m_s);
    return lineSetAt(street_, occlusion_, frame, truth, random_);
  }

  const std::shared_ptr<const PreparedMap>& map() const { return map_; }

 private:
  Street street_;
  OcclusionScene occlusion_;
  std::shared_ptr<const PreparedMap> map_;
  std::mt19937 random_;
};

}  // namespace lineloc::testing
