// The corners of the predicted view: model vertices in view where two visible
// model lines at an angle end (a roof line turning, a wall's edge meeting its
// roof or its foot). Where lines along the view leave the position along them
// open (a narrow street seen down its length), the image corners at such
// vertices fix it; model_alignment.h matches them with the robot's Förstner
// corners (robot/vision/corners/forstner_detector.h).
//
// A vertex is in view when a visible piece runs to its model line's own end
// (VisibleSegment::reaches_line_start / reaches_line_end): the frustum keeps it
// and no face hides it. Two ends meet when they lie within vertex_tolerance_m;
// the model's lines share their vertices' coordinates (line extraction snaps
// them, db/citymodel/line_extraction.h). Lines meeting at less than
// min_corner_angle_rad continue one another (a façade bending slightly) and
// make no corner the image could locate along them. A vertex where a piece
// ends without a partner at an angle is no corner either: a roof line running
// on into its neighbour's, say.
#pragma once

#include <Eigen/Core>
#include <cmath>
#include <vector>

#include "backbone/visibility/visible_lines.h"

namespace lineloc {

struct VisibleCorner {
  Eigen::Vector3d p_world = Eigen::Vector3d::Zero();
  // The smallest visibility weight of the pieces meeting there.
  double weight = 1.0;
  // A ground line ends there: the vertex is a building's foot, surveyed less
  // well than its roof (AlignmentOptions::ground_line_sigma_m).
  bool on_ground = false;
  // The visible pieces ending there (indices into visibleCorners' input).
  std::vector<int> pieces;
};

struct CornerOptions {
  double vertex_tolerance_m = 0.01;
  double min_corner_angle_rad = 30.0 * M_PI / 180.0;
};

std::vector<VisibleCorner> visibleCorners(const std::vector<VisibleSegment>& visible,
                                          const CornerOptions& options);

}  // namespace lineloc
