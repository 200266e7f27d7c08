// Search for the camera pose when the prior is too poor for gated matching
// (paper §3.2: "the camera position is only approximately known") — a start
// from DGPS and compass, 5-10 m and a few degrees off, or a return after a
// long outage.
//
// Roll and pitch are taken from the prior (gravity fixes them to a fraction of
// a degree) and so is the height, which the caller knows from the ground (a
// ground robot's camera rides at a known height above it); position x, y and
// yaw psi are searched on a grid over the prior's range_sigma region,
// R = Rz(dpsi) R_prior. Each hypothesis is scored by oriented chamfer coverage
// (Shotton et al., PAMI 2008; oriented_distance_map.h): the visible model
// lines are projected and sampled every s pixels; a sample q with direction
// theta is covered by c(q) = 1 - min(d_theta(q), tau) / tau. With C = s sum c
// the covered model length and L the projected model length (pixels), the
// score is C / sqrt(L): C alone favours views that project more model lines
// onto a busy image, C / L views that see a single line well. Image lines of
// things not in the model cost nothing; model lines they hide lower every
// hypothesis alike.
//
// Visibility (hidden-line removal) depends on the position: it is computed
// once per cell of a coarser grid, with a field of view widened by the yaw
// range, and shared by the hypotheses in that cell. Positions under a roof
// (inside a building) are skipped. The search runs coarse to fine: the best
// distinct coarse hypotheses (non-maximum suppression) are searched again on a
// finer grid around themselves, height included, with a sharper distance map.
// Cells, positions and hypotheses are shared out among `threads` threads.
#pragma once

#include <Eigen/Geometry>
#include <vector>

#include "backbone/matching/oriented_distance_map.h"
#include "backbone/visibility/visible_lines.h"

namespace lineloc {

struct SearchLevel {
  // Half-widths of the grid around a fine level's start (the coarse level's
  // come from the prior), and its steps.
  double position_range_m = 0.0;
  double yaw_range_rad = 0.0;
  double height_range_m = 0.0;
  double position_step_m = 0.5;
  double yaw_step_rad = 0.5 * M_PI / 180.0;
  double height_step_m = 0.1;
  DistanceMapOptions distances;
};

struct PoseSearchOptions {
  // Half-width of the searched region in prior standard deviations, and its caps.
  double range_sigma = 3.0;
  double max_position_range_m = 25.0;
  double max_yaw_range_rad = 10.0 * M_PI / 180.0;
  // The yaw range is at least this (a compass-only heading is often overconfident).
  double min_yaw_range_rad = 2.0 * M_PI / 180.0;
  SearchLevel coarse{0.0, 0.0, 0.0, 0.5, 0.5 * M_PI / 180.0, 0.1, {15.0, 16.0, 2}};
  SearchLevel fine{0.25, 0.25 * M_PI / 180.0, 0.2, 0.125, 0.125 * M_PI / 180.0,
                   0.1,  {15.0, 6.0, 1}};
  // Spacing of the samples along projected model lines (pixels).
  double sample_spacing_px = 6.0;
  // Views that project less model length than this (pixels) are not scored.
  double min_model_length_px = 200.0;
  // Side of the cells that share one visibility computation (metres).
  double visibility_cell_m = 3.0;
  // Distinct hypotheses kept after the coarse level, best first.
  int max_hypotheses = 12;
  // Hypotheses closer than both of these are the same (non-maximum suppression).
  double distinct_position_m = 1.0;
  double distinct_yaw_rad = 1.0 * M_PI / 180.0;
  // Hidden-line removal for scoring: coarser sampling than for alignment.
  VisibilityOptions visibility{.sample_spacing_px = 16.0};
  // Threads sharing the cells and hypotheses of one search (0: one per core).
  int threads = 0;
};

struct Coverage {
  double covered_px = 0.0;
  double model_px = 0.0;
  // C / sqrt(L); 0 below min_model_length_px.
  double score = 0.0;
};

struct PoseHypothesis {
  Eigen::Isometry3d T_world_camera = Eigen::Isometry3d::Identity();
  // At the fine level.
  Coverage coverage;
};

// Coverage C / sqrt(L) of the visible model lines seen from one pose against a
// distance map, sampled every options.sample_spacing_px pixels; 0 below
// options.min_model_length_px.
Coverage measureCoverage(const std::vector<VisibleSegment>& visible,
                         const Eigen::Isometry3d& T_world_camera, const PinholeCamera& camera,
                         const OrientedDistanceMap& map, const PoseSearchOptions& options);

class PoseSearch {
 public:
  // `lines` and `scene` must outlive the search.
  PoseSearch(const std::vector<ModelSegment>& lines, const OcclusionScene& scene,
             const PinholeCamera& camera, const PoseSearchOptions& options);

  // Distinct hypotheses, best score first; empty when every searched position
  // is inside a building or nothing can be seen.
  std::vector<PoseHypothesis> search(const std::vector<ImageSegment>& image,
                                     const PoseWithCovariance& prior) const;

 private:
  std::vector<VisibleSegment> visibleFrom(const Eigen::Vector3d& position_world,
                                          const Eigen::Matrix3d& R_world_camera,
                                          double yaw_range_rad) const;
  bool underRoof(const Eigen::Vector3d& position_world) const;
  struct GridPose {
    Eigen::Vector3d position_world;
    // Rotation about the world z axis applied to the prior's orientation.
    double yaw_offset_rad = 0.0;
    Coverage coverage;
  };
  // The best pose on the fine grid around `start`, scored against the fine level's map.
  GridPose refine(const GridPose& start, const Eigen::Matrix3d& R_prior,
                  const OrientedDistanceMap& map) const;
  std::vector<GridPose> distinctBest(std::vector<GridPose> poses) const;
  Eigen::Isometry3d poseOf(const GridPose& grid, const Eigen::Matrix3d& R_prior) const;

  const std::vector<ModelSegment>& lines_;
  const OcclusionScene& scene_;
  PinholeCamera camera_;
  PoseSearchOptions options_;
};

}  // namespace lineloc
