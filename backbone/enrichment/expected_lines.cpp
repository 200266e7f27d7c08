#include "backbone/enrichment/expected_lines.h"

namespace lineloc {
namespace {

// A face this close to the line's middle is the line's own wall.
constexpr double kOwnWallClearance_m = 0.1;

}  // namespace

ExpectedLines::ExpectedLines(std::vector<KnownLearntLine> lines, const ExpectedLineOptions& options)
    : lines_(std::move(lines)),
      options_(options),
      frames_(lines_.size(), 0),
      last_ns_(lines_.size(), 0) {}

bool ExpectedLines::expects(const EnrichmentFrame& frame, const OcclusionScene& scene,
                            const KnownLearntLine& line) const {
  const Eigen::Vector3d middle = 0.5 * (line.start_world + line.end_world);
  const Eigen::Vector3d camera = frame.T_world_camera.pose.translation();
  if ((middle - camera).norm() > options_.max_depth_m) {
    return false;
  }
  const Eigen::Isometry3d T_camera_world = frame.T_world_camera.pose.inverse();
  const Eigen::Vector3d a = T_camera_world * line.start_world;
  const Eigen::Vector3d b = T_camera_world * line.end_world;
  if (!(a.z() > 0.0 && b.z() > 0.0)) {
    return false;
  }
  const Eigen::Vector2d pa = frame.camera.project(a), pb = frame.camera.project(b);
  const auto inside = [&](const Eigen::Vector2d& pixel) {
    return pixel.x() >= 0.0 && pixel.y() >= 0.0 && pixel.x() < frame.camera.width &&
           pixel.y() < frame.camera.height;
  };
  if (!inside(pa) || !inside(pb) || (pb - pa).norm() < options_.min_length_px) {
    return false;
  }
  if (posePlacementSigma(frame.T_world_camera, line.plane, middle,
                         line.end_world - line.start_world) > options_.max_placement_sigma_m) {
    return false;
  }
  return !scene.blocked(camera, middle, kOwnWallClearance_m);
}

void ExpectedLines::observe(const EnrichmentFrame& frame, const OcclusionScene& scene) {
  for (size_t i = 0; i < lines_.size(); ++i) {
    if (expects(frame, scene, lines_[i])) {
      ++frames_[i];
      last_ns_[i] = std::max(last_ns_[i], frame.stamp_ns);
    }
  }
}

std::vector<ExpectedLine> ExpectedLines::expected() const {
  std::vector<ExpectedLine> expected;
  for (size_t i = 0; i < lines_.size(); ++i) {
    if (frames_[i] >= options_.min_frames) {
      expected.push_back({lines_[i].id, last_ns_[i]});
    }
  }
  return expected;
}

}  // namespace lineloc
