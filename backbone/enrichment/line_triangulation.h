// A 3D line from the image segments several views saw of it (paper §3.1:
// the database "enriched with more lines, which are extracted from camera
// images"), by least squares over the views, with its covariance.
//
// The line is kept in the orthonormal representation of its Plücker
// coordinates (d, m), m = p x d for a point p on it (Bartoli & Sturm,
// "Structure-from-motion using lines: representation, triangulation, and
// bundle adjustment", CVIU 100(3), 2005, §3.2): (U, W) in SO(3) x SO(2),
//   U = [d / |d|, m / |m|, d x m / |d x m|],  W = [[w1, -w2], [w2, w1]],
//   (w1, w2) = (|d|, |m|) / sqrt(|d|^2 + |m|^2),
// updated by U <- U Exp([theta]x) and W <- W R(phi): four parameters, the
// line's degrees of freedom, with no constraint to keep. The coordinates are
// taken about the mean of the cameras' centres, so that |m|, the line's
// distance from there, is never zero for a line the cameras see.
//
// A view with camera centre c and rotation R (world from camera) and
// intrinsics K sees the line as the image line l = K^-T R^T (m - c x d)
// (the normal of the plane through the camera and the line); each endpoint q
// of its segment gives the residual r = l . [q; 1] / |(l1, l2)|, its
// variance n^T Sigma_q n (n the line's unit normal in the image) plus that
// which the view's pose covariance causes (propagated by numeric
// derivatives). The start is the linear triangulation (the two points
// spanning the null space of the views' planes [R K^T l; -(R K^T l) . c],
// Hartley & Zisserman 2nd ed. §12.7), refined by Gauss-Newton; the
// covariance is (J^T J)^-1 of the whitened residuals.
//
// A line constrained to a plane (a window edge on a model wall) has two
// parameters, its direction's angle and its offset within the plane, and is
// estimated the same way.
//
// Conditioning. The line is refused, with the reason, when fewer than
// min_views views see it, when no two camera centres are min_baseline_m
// apart, or when no two views' planes meet at min_plane_angle_rad: a line
// seen from one place, or parallel to the cameras' path (a window's top edge
// seen driving along its façade), lies in one plane with all of them and is
// not fixed by them. In a given plane, the views' planes must meet that one
// at min_plane_angle_rad instead, which fixes even such a line. A line is
// refused, too, when any view's residuals, chi^2 over its two endpoints,
// exceed max_view_chi2: each view must see the line within its uncertainty.
//
// Extent. Each endpoint's ray, back-projected, meets the line (its closest
// point) at a position along it; the line's segment runs over the positions
// at least two views reach, so that one view's overlong segment does not
// stretch it.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <optional>
#include <string>
#include <vector>

#include "common/camera/camera_calibration.h"
#include "common/geometry/pose.h"
#include "common/messages/messages.h"

namespace lineloc {

// One view's segment of the line: pixels of the undistorted image.
struct LineObservation {
  PinholeCamera camera;
  PoseWithCovariance T_world_camera;
  ImageSegment segment;
};

// The plane n . x = offset (n a unit normal, world frame).
struct Plane {
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();
  double offset = 0.0;
};

struct LineTriangulationOptions {
  int min_views = 3;
  double min_baseline_m = 0.5;
  double min_plane_angle_rad = 2.0 * M_PI / 180.0;
  // chi^2_2(0.9973): a view's two endpoint residuals beyond it refuse the line.
  double max_view_chi2 = 11.83;
  int max_iterations = 20;
};

struct TriangulatedLine {
  Eigen::Vector3d start_world = Eigen::Vector3d::Zero();
  Eigen::Vector3d end_world = Eigen::Vector3d::Zero();
  // Plücker coordinates in the world frame: unit direction and moment.
  Eigen::Vector3d direction = Eigen::Vector3d::UnitX();
  Eigen::Vector3d moment = Eigen::Vector3d::Zero();
  // Covariance of each endpoint (m^2) across the line: what the views leave
  // open of where the line lies, not of how far it runs.
  Eigen::Matrix3d start_covariance = Eigen::Matrix3d::Zero();
  Eigen::Matrix3d end_covariance = Eigen::Matrix3d::Zero();
  // Parameters estimated (4, or 2 in a plane) and their covariance.
  int dof = 4;
  Eigen::Matrix4d parameter_covariance = Eigen::Matrix4d::Zero();
  // Each view's chi^2 over its two endpoints, in the order given.
  std::vector<double> view_chi2;
};

struct LineTriangulation {
  std::optional<TriangulatedLine> line;
  // Why there is none.
  std::string refusal;
};

// The line the views saw (see above); in `plane` when one is given.
LineTriangulation triangulateLine(const std::vector<LineObservation>& views,
                                  const LineTriangulationOptions& options,
                                  const std::optional<Plane>& plane = std::nullopt);

}  // namespace lineloc
