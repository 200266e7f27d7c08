// Hidden-line removal for the predicted view (paper §3.2: lines at the back of
// buildings are invisible). Each model line is clipped to the camera's view
// frustum, sampled along its length, and every sample is tested for a clear
// line of sight from the camera centre through the building faces
// (OcclusionScene). Consecutive visible samples form the visible pieces.
//
// Visibility depends on the camera position only, so its uncertainty comes
// from the position block P of the predicted pose covariance: each sample is
// also tested from the 2n = 6 sigma points c +- sqrt(n) sqrt(lambda_i) v_i of
// P = V diag(lambda) V^T (Julier & Uhlmann, "Unscented filtering and nonlinear
// estimation", Proc. IEEE 2004, eq. 12 with kappa = 0). A piece's weight is the
// mean fraction of those 7 viewpoints that see its samples: 1 for a line
// surely visible, lower near occluding edges, so the matcher trusts it less.
//
// A visible line is an image edge only where the surfaces on its two sides
// differ. A sample is hidden when the rays through the pixels
// `contrast_probe_px` either side of the projected line both meet faces of one
// building whose planes are within `same_plane_angle_rad` (a ray that meets no
// face sees sky or ground, or a line the model gives no faces). So the two
// creases of a footprint jog a few centimetres deep show only while the narrow
// wall between them faces the camera and is wider than the probe; seen from its
// back side, the near wall's crease lies against the far wall, which has the
// same orientation and façade, and no edge shows.
//
// Under a known sun (`sunlight`), two faces of one building at an angle show
// no edge either where the light they receive differs by less than
// `min_irradiance_difference` of full sun (E(n) of common/geometry/sunlight.h):
// the vertical corner between two walls the sun lights alike. Without that
// rule, the window columns inset from such corners on a street view fit the
// model's outline as seen from 0.25-0.35 m behind the true camera along its
// view, and tracking settles there, precise and wrong. A probed point is in
// shadow where the ray from it towards the sun meets a face: the shadow
// another building casts.
//
// The same probes predict a piece's polarity, which side of it is brighter,
// where the model can tell: the sky, where a ray upwards meets no face, is
// brighter than a façade against it (a roof line or the top of a silhouette).
// The samples of a piece vote; a piece has a polarity only where all of them
// predict it. The matcher keeps image segments of the other polarity off it
// (line_matcher.h). The sun might tell too, the lit face of a corner against
// its shaded one, but windows and shop fronts darker than the shaded wall sit
// at many corners: over the first minute of the demo's drive (the LinePolarity
// test, tests/integration/drive/test_unmodelled_lines.cpp) 16 of 99 such
// predictions disagreed with the image, against none of 372 from the sky.
//
// The probes also tell which side of a piece its own façade lies on
// (facade_side): the side whose ray meets a face where the other's meets none,
// or one farther by facade_depth_ratio. A roof line's façade lies below it, a
// silhouette's on its building's side; a crease has faces on both sides and
// gets none. Detail the model lacks (window frames, doors) lies on that side
// only, and the alignment leaves out matches there (model_alignment.h).
#pragma once

#include <Eigen/Core>
#include <cmath>
#include <cstdint>
#include <optional>
#include <vector>

#include "backbone/visibility/occlusion_scene.h"
#include "common/camera/camera_calibration.h"
#include "common/geometry/pose.h"
#include "common/geometry/sunlight.h"

namespace lineloc {

struct ModelSegment {
  int64_t id = 0;
  int kind = 0;
  Eigen::Vector3d start_world = Eigen::Vector3d::Zero();
  Eigen::Vector3d end_world = Eigen::Vector3d::Zero();
  // A learnt line's (LineKind::kLearnt) standard deviation across it (m); a
  // learnt line is an edge of paint on its face, not of shape, and shows
  // wherever it is in view. 0 for the model's lines.
  double sigma_m = 0.0;
};

struct VisibleSegment {
  int64_t model_line_id = 0;
  int kind = 0;
  Eigen::Vector3d start_world = Eigen::Vector3d::Zero();
  Eigen::Vector3d end_world = Eigen::Vector3d::Zero();
  // Fraction (0, 1] of the viewpoints under the position uncertainty that see it.
  double weight = 1.0;
  // +1 when the side left of its projection start -> end (image, y down) is
  // predicted brighter, -1 when the right one is, 0 when the model cannot tell.
  int polarity = 0;
  // The side, read the same way, that the line's own façade is on: +1 left,
  // -1 right, 0 both (a crease) or unknown.
  int facade_side = 0;
  // The piece runs to its model line's own start (end): that vertex is inside
  // the frustum and seen, not cut off by the frustum or by a face in front.
  bool reaches_line_start = false;
  bool reaches_line_end = false;
  // The line's ModelSegment::sigma_m.
  double sigma_m = 0.0;
};

struct VisibilityOptions {
  double near_m = 0.3;
  double far_m = 400.0;
  // How far outside the image a line may reach and still count (pixels).
  double image_margin_px = 20.0;
  double sample_spacing_px = 8.0;
  int max_samples_per_line = 64;
  // Samples closer than this to the sampled point do not block it (metres).
  double surface_clearance_m = 0.05;
  double min_visible_length_px = 10.0;
  // About the front end's blur (Gaussian sigma 1 px, then a 3x3 Sobel): a
  // narrower strip of wall gives no edge of its own.
  double contrast_probe_px = 1.5;
  double same_plane_angle_rad = 10.0 * M_PI / 180.0;
  // A probe whose ray meets a face nearer by this factor than the other
  // probe's (or the only one that meets a face) sees the line's own façade.
  double facade_depth_ratio = 1.1;
  // The sun over the scene, when known; then faces lit alike show no edge.
  std::optional<Sunlight> sunlight = std::nullopt;
  double min_irradiance_difference = 0.1;
  // Predict which side of each visible piece is brighter (its polarity)
  // where the sky lies on one side of it.
  bool predict_polarity = true;
  // Threads sharing the lines (0: one per core); 1 where the caller already
  // runs on every core (the pose search's cells).
  int threads = 1;
};

// The visible pieces of `lines` seen from `T_world_camera` (with covariance)
// by `camera`, in undistorted pixels of that camera.
std::vector<VisibleSegment> visibleSegments(const std::vector<ModelSegment>& lines,
                                            const OcclusionScene& scene,
                                            const PoseWithCovariance& T_world_camera,
                                            const PinholeCamera& camera,
                                            const VisibilityOptions& options);

// Clips the segment (camera frame) to the frustum; false when nothing is left.
bool clipToFrustum(Eigen::Vector3d& start_camera, Eigen::Vector3d& end_camera,
                   const PinholeCamera& camera, const VisibilityOptions& options);

}  // namespace lineloc
