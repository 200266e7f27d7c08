// Image edges where a pose's model sees open sky: evidence against the pose
// that coverage alone does not give (paper §3.2: "a false match gives a
// precise but wrong pose").
//
// From the camera pose T_world_camera, the viewing ray of an image point q is
// d = R_world_camera K^-1 (q, 1) / |.|. The point is in open sky when d rises
// at least min_elevation_rad above the horizon and meets no building face,
// nor does the ray lowered by margin_px / f_x towards the ground: the roof
// line itself borders the sky, and a pixel of noise must not put it there.
// Sky is featureless, so an image edge there is something the pose does not
// explain. A search settled a house's width along a street, or a window row
// taken for a roof line, covers as many model lines as the true pose does,
// but it leaves façade detail where its model shows sky.
//
// Below the horizon a ray that meets no face meets the ground, which the
// model does not hold, so nothing is counted there; min_elevation_rad also
// leaves out buildings far beyond the map around the robot, low over the
// horizon, which no hypothesis holds either. Things that are in no model and
// stand against the sky (trees, lamp posts) count against every pose that
// sees sky behind them alike.
#pragma once

#include <Eigen/Geometry>
#include <vector>

#include "backbone/visibility/occlusion_scene.h"
#include "common/camera/camera_calibration.h"
#include "common/messages/messages.h"

namespace lineloc {

struct SkyEdgeOptions {
  // About 6 degrees: a ten-storey building 300 m away rises no higher.
  double min_elevation_rad = 0.1;
  double margin_px = 4.0;
  // Samples along each image segment, and the shortest segment sampled.
  double sample_spacing_px = 6.0;
  double min_segment_length_px = 15.0;
  // A ray meeting no face within this distance meets none.
  double reach_m = 1000.0;
};

// Length (pixels) of the image segments that lie in open sky seen from
// T_world_camera, in steps of options.sample_spacing_px.
double skyEdgeLength(const std::vector<ImageSegment>& image,
                     const Eigen::Isometry3d& T_world_camera, const PinholeCamera& camera,
                     const OcclusionScene& scene, const SkyEdgeOptions& options);

}  // namespace lineloc
