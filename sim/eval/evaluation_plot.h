// The picture of an evaluation: a top view of the ground-truth and estimated
// trajectories over the building footprints, and the position and attitude
// errors over time against the target thresholds. Drawn with OpenCV.
#pragma once

#include <opencv2/core.hpp>
#include <vector>

#include "common/trajectory/tum_trajectory.h"
#include "sim/eval/trajectory_evaluation.h"
#include "sim/render/scene_mesh.h"

namespace lineloc {

struct PlotLayout {
  int width_px = 1200;
  int map_height_px = 800;
  int graph_height_px = 300;
  // World margin around the trajectories in the top view (m).
  double map_margin_m = 25.0;
};

// `buildings` (may be null) supplies the footprints: its wall and roof
// triangles seen from above. Returns a CV_8UC3 image.
cv::Mat drawEvaluationPlot(const std::vector<StampedPose>& ground_truth,
                           const std::vector<StampedPose>& estimate,
                           const TrajectoryEvaluation& evaluation, const EvaluationOptions& options,
                           const SceneMesh* buildings, const PlotLayout& layout = {});

}  // namespace lineloc
