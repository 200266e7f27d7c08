#include "backbone/matching/pose_search.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <utility>

#include "common/parallel/parallel_for.h"

namespace lineloc {
namespace {

// Camera depth below which a projected piece is cut (metres).
constexpr double kNearDepthM = 0.3;
// Height of the ray that tests whether a position is under a roof (metres).
constexpr double kRoofProbeHeightM = 1000.0;

Eigen::Matrix3d yawed(const Eigen::Matrix3d& R_world_camera, double yaw_offset_rad) {
  return Eigen::AngleAxisd(yaw_offset_rad, Eigen::Vector3d::UnitZ()).toRotationMatrix() *
         R_world_camera;
}

// Cuts the part of a camera-frame segment nearer than kNearDepthM; false when
// nothing is left.
bool clipNear(Eigen::Vector3d& a, Eigen::Vector3d& b) {
  if (a.z() < kNearDepthM && b.z() < kNearDepthM) {
    return false;
  }
  if (a.z() < kNearDepthM) {
    a += (b - a) * ((kNearDepthM - a.z()) / (b.z() - a.z()));
  } else if (b.z() < kNearDepthM) {
    b += (a - b) * ((kNearDepthM - b.z()) / (a.z() - b.z()));
  }
  return true;
}

// Liang-Barsky clipping of the 2D segment a-b to [0, w] x [0, h].
bool clipToImage(Eigen::Vector2d& a, Eigen::Vector2d& b, double width, double height) {
  const Eigen::Vector2d d = b - a;
  double t0 = 0.0;
  double t1 = 1.0;
  const double p[4] = {-d.x(), d.x(), -d.y(), d.y()};
  const double q[4] = {a.x(), width - a.x(), a.y(), height - a.y()};
  for (int i = 0; i < 4; ++i) {
    if (p[i] == 0.0) {
      if (q[i] < 0.0) {
        return false;
      }
      continue;
    }
    const double t = q[i] / p[i];
    if (p[i] < 0.0) {
      t0 = std::max(t0, t);
    } else {
      t1 = std::min(t1, t);
    }
  }
  if (t0 >= t1) {
    return false;
  }
  const Eigen::Vector2d start = a + t0 * d;
  b = a + t1 * d;
  a = start;
  return true;
}

// Offsets -n step .. n step with n = floor(half_range / step), at least {0}.
std::vector<double> gridOffsets(double half_range, double step) {
  const int n = step > 0.0 ? static_cast<int>(std::floor(half_range / step + 1e-9)) : 0;
  std::vector<double> offsets;
  for (int i = -n; i <= n; ++i) {
    offsets.push_back(i * step);
  }
  return offsets;
}

}  // namespace

PoseSearch::PoseSearch(const std::vector<ModelSegment>& lines, const OcclusionScene& scene,
                       const PinholeCamera& camera, const PoseSearchOptions& options)
    : lines_(lines), scene_(scene), camera_(camera), options_(options) {}

Eigen::Isometry3d PoseSearch::poseOf(const GridPose& grid, const Eigen::Matrix3d& R_prior) const {
  Eigen::Isometry3d T_world_camera = Eigen::Isometry3d::Identity();
  T_world_camera.linear() = yawed(R_prior, grid.yaw_offset_rad);
  T_world_camera.translation() = grid.position_world;
  return T_world_camera;
}

// Greedy non-maximum suppression: the best poses, each farther than the
// distinct thresholds from every pose kept before it.
std::vector<PoseSearch::GridPose> PoseSearch::distinctBest(std::vector<GridPose> poses) const {
  std::sort(poses.begin(), poses.end(), [](const GridPose& a, const GridPose& b) {
    return a.coverage.score > b.coverage.score;
  });
  std::vector<GridPose> kept;
  for (const GridPose& pose : poses) {
    if (static_cast<int>(kept.size()) >= options_.max_hypotheses || pose.coverage.score <= 0.0) {
      break;
    }
    const bool duplicate = std::any_of(kept.begin(), kept.end(), [&](const GridPose& other) {
      return (other.position_world - pose.position_world).head<2>().norm() <
                 options_.distinct_position_m &&
             std::abs(other.yaw_offset_rad - pose.yaw_offset_rad) < options_.distinct_yaw_rad;
    });
    if (!duplicate) {
      kept.push_back(pose);
    }
  }
  return kept;
}

bool PoseSearch::underRoof(const Eigen::Vector3d& position_world) const {
  return scene_.blocked(position_world,
                        position_world + Eigen::Vector3d(0.0, 0.0, kRoofProbeHeightM), 0.0);
}

std::vector<VisibleSegment> PoseSearch::visibleFrom(const Eigen::Vector3d& position_world,
                                                    const Eigen::Matrix3d& R_world_camera,
                                                    double yaw_range_rad) const {
  PoseWithCovariance viewpoint;
  viewpoint.pose.linear() = R_world_camera;
  viewpoint.pose.translation() = position_world;
  viewpoint.covariance.setZero();
  // The image edge at angle alpha = atan(cx / fx) moves by fx (tan(alpha + r) - tan(alpha)).
  const double edge_rad = std::atan2(std::max(camera_.cx, camera_.width - camera_.cx), camera_.fx);
  const double widened_rad = std::min(edge_rad + yaw_range_rad, 0.49 * M_PI);
  VisibilityOptions options = options_.visibility;
  options.image_margin_px += camera_.fx * (std::tan(widened_rad) - std::tan(edge_rad));
  return visibleSegments(lines_, scene_, viewpoint, camera_, options);
}

Coverage measureCoverage(const std::vector<VisibleSegment>& visible,
                         const Eigen::Isometry3d& T_world_camera, const PinholeCamera& camera,
                         const OrientedDistanceMap& map, const PoseSearchOptions& options) {
  const Eigen::Isometry3d T_camera_world = T_world_camera.inverse();
  Coverage coverage;
  for (const VisibleSegment& segment : visible) {
    Eigen::Vector3d a = T_camera_world * segment.start_world;
    Eigen::Vector3d b = T_camera_world * segment.end_world;
    if (!clipNear(a, b)) {
      continue;
    }
    Eigen::Vector2d pa = camera.project(a);
    Eigen::Vector2d pb = camera.project(b);
    if (!clipToImage(pa, pb, camera.width, camera.height)) {
      continue;
    }
    const double length = (pb - pa).norm();
    if (length < options.sample_spacing_px) {
      continue;
    }
    coverage.covered_px += map.coveredLength(pa, pb, options.sample_spacing_px);
    coverage.model_px += length;
  }
  if (coverage.model_px >= options.min_model_length_px) {
    coverage.score = coverage.covered_px / std::sqrt(coverage.model_px);
  }
  return coverage;
}

PoseSearch::GridPose PoseSearch::refine(const GridPose& start, const Eigen::Matrix3d& R_prior,
                                        const OrientedDistanceMap& map) const {
  const SearchLevel& fine = options_.fine;
  const std::vector<VisibleSegment> visible =
      visibleFrom(start.position_world, yawed(R_prior, start.yaw_offset_rad), fine.yaw_range_rad);
  GridPose best = start;
  best.coverage = {};
  for (const double dx : gridOffsets(fine.position_range_m, fine.position_step_m)) {
    for (const double dy : gridOffsets(fine.position_range_m, fine.position_step_m)) {
      for (const double dz : gridOffsets(fine.height_range_m, fine.height_step_m)) {
        for (const double yaw : gridOffsets(fine.yaw_range_rad, fine.yaw_step_rad)) {
          GridPose pose{
              start.position_world + Eigen::Vector3d(dx, dy, dz), start.yaw_offset_rad + yaw, {}};
          pose.coverage = measureCoverage(visible, poseOf(pose, R_prior), camera_, map, options_);
          if (pose.coverage.score > best.coverage.score) {
            best = pose;
          }
        }
      }
    }
  }
  return best;
}

std::vector<PoseHypothesis> PoseSearch::search(const std::vector<ImageSegment>& image,
                                               const PoseWithCovariance& prior) const {
  const Eigen::Matrix3d R_prior = prior.pose.linear();
  const Eigen::Vector3d centre = prior.pose.translation();
  const Eigen::Matrix2d position_covariance = prior.covariance.block<2, 2>(0, 0);
  const Eigen::Matrix2d information = position_covariance.inverse();
  const double range = options_.range_sigma;
  const double half_x =
      std::min(range * std::sqrt(position_covariance(0, 0)), options_.max_position_range_m);
  const double half_y =
      std::min(range * std::sqrt(position_covariance(1, 1)), options_.max_position_range_m);
  const double yaw_range = std::clamp(range * std::sqrt(prior.covariance(5, 5)),
                                      options_.min_yaw_range_rad, options_.max_yaw_range_rad);
  const SearchLevel& coarse = options_.coarse;

  // The coarse positions inside the region and not under a roof, each with
  // the visibility cell it belongs to.
  std::map<std::pair<int, int>, int> cell_index;
  std::vector<Eigen::Vector3d> cell_centres;
  std::vector<std::pair<Eigen::Vector3d, int>> positions;
  for (const double dx : gridOffsets(half_x, coarse.position_step_m)) {
    for (const double dy : gridOffsets(half_y, coarse.position_step_m)) {
      const Eigen::Vector2d offset(dx, dy);
      const Eigen::Vector3d position = centre + Eigen::Vector3d(dx, dy, 0.0);
      const bool inside_region = offset.dot(information * offset) <= range * range ||
                                 offset.norm() <= coarse.position_step_m;
      if (!inside_region || underRoof(position)) {
        continue;
      }
      const std::pair<int, int> cell{
          static_cast<int>(std::lround(dx / options_.visibility_cell_m)),
          static_cast<int>(std::lround(dy / options_.visibility_cell_m))};
      const auto [found, added] = cell_index.emplace(cell, static_cast<int>(cell_centres.size()));
      if (added) {
        cell_centres.push_back(centre + options_.visibility_cell_m *
                                            Eigen::Vector3d(cell.first, cell.second, 0.0));
      }
      positions.emplace_back(position, found->second);
    }
  }
  std::vector<std::vector<VisibleSegment>> visible_by_cell(cell_centres.size());
  parallelFor(static_cast<int>(cell_centres.size()), options_.threads, [&](int cell) {
    visible_by_cell[cell] = visibleFrom(cell_centres[cell], R_prior, yaw_range);
  });

  const OrientedDistanceMap coarse_map(image, camera_.width, camera_.height, coarse.distances);
  const std::vector<double> yaws = gridOffsets(yaw_range, coarse.yaw_step_rad);
  std::vector<GridPose> scored(positions.size() * yaws.size());
  parallelFor(static_cast<int>(positions.size()), options_.threads, [&](int index) {
    const auto& [position, cell] = positions[index];
    for (size_t k = 0; k < yaws.size(); ++k) {
      GridPose& pose = scored[index * yaws.size() + k];
      pose = {position, yaws[k], {}};
      pose.coverage = measureCoverage(visible_by_cell[cell], poseOf(pose, R_prior), camera_,
                                      coarse_map, options_);
    }
  });

  const OrientedDistanceMap fine_map(image, camera_.width, camera_.height, options_.fine.distances);
  const std::vector<GridPose> starts = distinctBest(std::move(scored));
  std::vector<GridPose> refined(starts.size());
  parallelFor(static_cast<int>(starts.size()), options_.threads,
              [&](int i) { refined[i] = refine(starts[i], R_prior, fine_map); });
  std::vector<PoseHypothesis> hypotheses;
  for (const GridPose& pose : distinctBest(std::move(refined))) {
    hypotheses.push_back({poseOf(pose, R_prior), pose.coverage});
  }
  return hypotheses;
}

}  // namespace lineloc
