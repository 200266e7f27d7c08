// Moves the endpoints of two segments that meet at a corner onto the
// intersection of their lines.
//
// Near a corner the blurred edge bends, so edge chains stop a pixel or two
// short of it; the intersection of the two fitted lines is where the corner
// really is. Endpoints a (of line A) and b (of line B) snap when the lines
// cross at an angle alpha >= min_angle and the intersection x lies within
// radius of both. The snapped endpoint's position along A is then fixed by
// B's normal position at x: sigma_along_A = sqrt(var_normal_B(x)) / sin(alpha).
// Each endpoint snaps at most once: of all pairs that could, the closest
// (the larger distance of its two endpoints from x smallest) first. Every snap is
// kept as a junction: x with covariance A^-1 diag(var_A(x), var_B(x)) A^-T,
// A = [n_A^T; n_B^T] the two line normals.
#pragma once

#include <cstdint>
#include <vector>

#include "robot/vision/lines/line_segment.h"

namespace lineloc {

struct EndpointSnapOptions {
  double radius_px = 8.0;  // a chain broken near a corner can end ~6 px short of it
  double min_angle_rad = 0.35;
};

struct Junction {
  Eigen::Vector2d position;
  Eigen::Matrix2d covariance;
};

class EndpointSnapper {
 public:
  explicit EndpointSnapper(const EndpointSnapOptions& options);

  void snap(std::vector<LineSegment>& segments);

  // Where the last snap() met pairs of lines.
  const std::vector<Junction>& junctions() const { return junctions_; }

 private:
  struct Endpoint {
    Eigen::Vector2d position;
    int32_t segment;
    bool is_start;
    bool snapped;
  };
  // A pair that could snap: its endpoints' indices, the parameters s, u of x
  // along A and B, and the larger endpoint distance from x.
  struct Candidate {
    int32_t a, b;
    double s, u;
    double distance_px;
  };
  void addCandidate(const std::vector<LineSegment>& segments, int32_t a, int32_t b);
  void apply(std::vector<LineSegment>& segments, const Candidate& candidate);

  EndpointSnapOptions options_;
  double min_sin_angle_;
  std::vector<Endpoint> endpoints_;
  std::vector<Candidate> candidates_;
  std::vector<Junction> junctions_;
};

}  // namespace lineloc
