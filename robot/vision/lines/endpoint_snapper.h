// Moves the endpoints of two segments that meet at a corner onto the
// intersection of their lines.
//
// Near a corner the blurred edge bends, so edge chains stop a pixel or two
// short of it; the intersection of the two fitted lines is where the corner
// really is. Endpoints a (of line A) and b (of line B) snap when the lines
// cross at an angle alpha >= min_angle and the intersection x lies within
// radius of both. The snapped endpoint's position along A is then fixed by
// B's normal position at x: sigma_along_A = sqrt(var_normal_B(x)) / sin(alpha).
// Each endpoint snaps at most once, to the first partner found.
#pragma once

#include <cstdint>
#include <vector>

#include "robot/vision/lines/line_segment.h"

namespace lineloc {

struct EndpointSnapOptions {
  double radius_px = 3.0;
  double min_angle_rad = 0.35;
};

class EndpointSnapper {
 public:
  explicit EndpointSnapper(const EndpointSnapOptions& options);

  void snap(std::vector<LineSegment>& segments);

 private:
  struct Endpoint {
    Eigen::Vector2d position;
    int32_t segment;
    bool is_start;
    bool snapped;
  };
  bool trySnap(std::vector<LineSegment>& segments, Endpoint& a, Endpoint& b) const;

  EndpointSnapOptions options_;
  double min_sin_angle_;
  std::vector<Endpoint> endpoints_;
};

}  // namespace lineloc
