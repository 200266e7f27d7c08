// Association of the surface segments of many frames into 3D lines, and their
// triangulation in the plane of the model face they lie on (paper §3.1: the
// database "enriched with more lines, which are extracted from camera images").
//
// Association happens on the model's surface, where every segment already has
// a 3D place: a segment joins a track of the same building and plane (normals
// within plane_angle_rad, offsets within plane_offset_m) whose line runs
// within max_angle_rad of it, when both its ends lie within the gate
//   g = max(min_gate_m, gate_sigma * sigma_p)
// of the track's line (sigma_p its placement's standard deviation, from its
// pixels and the pose), it reaches within max_gap_m of the
// track's extent, and its brighter side agrees with the track's. It joins the
// nearest such track, else starts one. A track's line is the principal axis
// of its views' endpoints, in its plane.
//
// A track with min_views views is triangulated from them (triangulateLine,
// constrained to the plane), which refuses a line whose views do not all see
// it within their uncertainty: something in front of the wall (a van's side,
// a sign on a pole) lands on the wall at a place that moves with the viewpoint
// and does not pass. Where the views fix the line without the plane too (a
// line not parallel to the path), that free line must lie in the plane: a
// line whose free triangulation puts an end off the plane by more than
// off_plane_sigma standard deviations (n^T Sigma n of that end) is something
// in front of the wall (a tree's trunk beside it), not on it. Only an end
// known to max_plane_test_sigma_m across the plane can refute it: beyond
// that the linearised covariance of a nearly degenerate line (one almost
// parallel to the path) understates its error.
//
// Each track keeps at most max_views views: the first max_views - 1 and the
// latest, so that its baseline only grows. A track with fewer views than a
// line needs and none since a given time may be forgotten (forgetStale): a
// segment seen once, in passing, keeps no memory.
#pragma once

#include <cstdint>
#include <unordered_map>
#include <vector>

#include "backbone/enrichment/line_triangulation.h"
#include "backbone/enrichment/surface_observations.h"

namespace lineloc {

struct SurfaceLineTrackOptions {
  double plane_angle_rad = 2.0 * M_PI / 180.0;
  double plane_offset_m = 0.05;
  double max_angle_rad = 3.0 * M_PI / 180.0;
  double gate_sigma = 3.0;
  double min_gate_m = 0.02;
  double max_gap_m = 0.5;
  int max_views = 30;
  double off_plane_sigma = 3.0;
  double max_plane_test_sigma_m = 0.05;
  LineTriangulationOptions triangulation;
};

// A 3D line learnt from the images, with its support.
struct LineCandidate {
  TriangulatedLine line;
  int64_t building_id = 0;
  Plane plane;
  Eigen::Vector3d brighter_side = Eigen::Vector3d::Zero();
  int views = 0;   // every view associated, beyond those kept
  int robots = 0;  // distinct robots among the kept views
  int64_t first_stamp_ns = 0;
  int64_t last_stamp_ns = 0;
};

class SurfaceLineTracks {
 public:
  explicit SurfaceLineTracks(const SurfaceLineTrackOptions& options);

  void add(const SurfaceSegment& segment);

  // Every track with enough views that triangulates in its plane and that
  // the views do not place off it.
  std::vector<LineCandidate> candidates() const;

  // Forgets the tracks with fewer than triangulation.min_views views whose
  // last view is older than `before_ns`.
  void forgetStale(int64_t before_ns);

  size_t trackCount() const;
  // Views the tracks keep.
  size_t viewCount() const;

 private:
  struct Track {
    int64_t building_id = 0;
    Plane plane;
    Eigen::Vector3d point = Eigen::Vector3d::Zero();
    Eigen::Vector3d direction = Eigen::Vector3d::UnitX();
    double along_min = 0.0;
    double along_max = 0.0;
    Eigen::Vector3d brighter_side = Eigen::Vector3d::Zero();
    int views_seen = 0;
    int64_t first_stamp_ns = 0;
    int64_t last_stamp_ns = 0;
    std::vector<SurfaceSegment> views;
  };

  // How far (m) the segment lies from the track's line, or a negative value
  // when it does not pass the gate.
  double distanceInGate(const Track& track, const SurfaceSegment& segment) const;
  static void fit(Track& track);
  // Whether the views, without the plane, place the line off it (see above).
  bool offPlane(const std::vector<LineObservation>& views, const Plane& plane) const;

  SurfaceLineTrackOptions options_;
  std::unordered_map<int64_t, std::vector<Track>> tracks_by_building_;
};

}  // namespace lineloc
