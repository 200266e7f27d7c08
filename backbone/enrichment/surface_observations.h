// What a well-localised frame offers the map (paper §3.1): the image segments
// that no visible model line explains, each placed on the model face it lies
// on, the raw material of enrichment.
//
// A segment contributes only where the frame's pose places it on the wall to
// within max_placement_sigma_m across the line: the pose's error is shared by
// every segment of the frame and by the frames around it, so triangulation
// does not average it out as it does the pixels'. A ray moved by d meets the
// wall moved by P d, P = I - r n^T / (n . r) (r the ray, n the wall's normal:
// a ray that grazes the wall moves far along it); a pose error e = [dp;
// dtheta] moves the ray at the segment's middle X by J e, J = [I, -[X - t]x]
// (t the camera's centre). With u the unit direction in the wall across the
// line, the pose's part is sigma_p^2 = u^T P J Sigma J^T P^T u. The pixels'
// error across the segment (the mean of its ends' variances across it) moves
// the ray by d / f per pixel at distance d: m, adding (u^T P m)^2 sigma_px^2
// to the placement's whole variance. A fix that leaves the position along a
// façade open still places the façade's horizontal edges, and a wall seen at
// a grazing angle places nothing well.
//
// A segment is explained when a visible model line, projected, runs within
// explained_angle_rad of it, both its endpoints lie within
// explained_distance_px of that line, and the two overlap along it: the
// matcher has (or could have) used it.
//
// Under a known sun, a segment that the model's cast shadow explains is left
// out too: of two points shadow_probe_m either side of it on the wall, one is
// lit and the other in a shadow the model casts (a ray towards the sun meets
// a face). Light is not structure: the boundary moves with the hour.
//
// An unexplained segment is placed by casting the rays through two points a
// tenth of its length in from its ends: both must meet a face of one building
// in one plane (normals within plane_angle_rad, the points within
// plane_offset_m of the plane through either), else the segment is not on the
// model's surface (a lamp post, a tree, a car's roof line seen against a wall
// at another depth) and is left out. Its ends are where their own rays meet
// that plane. Rays through a pixel either side of its middle find the side
// its polarity says is brighter, as a direction in the plane, so that a
// window frame's outer and inner edges, a few centimetres apart, are told
// apart by which side is bright.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "backbone/enrichment/line_triangulation.h"
#include "backbone/visibility/occlusion_scene.h"
#include "backbone/visibility/visible_lines.h"

namespace lineloc {

// One frame as the backbone answered it: its segments (undistorted pixels),
// the pose it answered with, and the model lines visible from there.
struct EnrichmentFrame {
  std::string robot_id;
  int64_t stamp_ns = 0;
  PinholeCamera camera;
  PoseWithCovariance T_world_camera;
  std::vector<ImageSegment> segments;
  std::vector<VisibleSegment> visible;
  // Unit vector towards the sun, when known.
  std::optional<Eigen::Vector3d> towards_sun_world;
};

// An unexplained segment on a model face.
struct SurfaceSegment {
  std::string robot_id;
  int64_t stamp_ns = 0;
  LineObservation view;
  int64_t building_id = 0;
  Plane plane;
  Eigen::Vector3d start_world = Eigen::Vector3d::Zero();
  Eigen::Vector3d end_world = Eigen::Vector3d::Zero();
  // Unit direction in the plane, across the segment, towards its brighter
  // side; zero when its polarity is unknown.
  Eigen::Vector3d brighter_side = Eigen::Vector3d::Zero();
  // Distance from the camera to the segment's middle (m).
  double depth_m = 0.0;
  // Standard deviations of its place across the line, from pose and pixels,
  // and from the pose alone (m; see above).
  double placement_sigma_m = 0.0;
  double pose_placement_sigma_m = 0.0;
};

struct SurfaceObservationOptions {
  double max_placement_sigma_m = 0.03;
  double min_length_px = 15.0;
  double explained_distance_px = 3.0;
  double explained_angle_rad = 2.0 * M_PI / 180.0;
  double plane_angle_rad = 5.0 * M_PI / 180.0;
  double plane_offset_m = 0.05;
  double shadow_probe_m = 0.05;
};

struct SurfaceObservations {
  std::vector<SurfaceSegment> segments;
  int explained = 0;
  int too_short = 0;
  int off_surface = 0;
  int shadow_edges = 0;
  int imprecise = 0;
};

// sigma_p above: the standard deviation, across a line through `point` along
// `direction` in `plane`, of where the camera's ray through the point meets
// the plane, that the pose's error causes.
double posePlacementSigma(const PoseWithCovariance& T_world_camera, const Plane& plane,
                          const Eigen::Vector3d& point, const Eigen::Vector3d& direction);

SurfaceObservations observeSurfaceSegments(const EnrichmentFrame& frame,
                                           const OcclusionScene& scene,
                                           const SurfaceObservationOptions& options);

}  // namespace lineloc
