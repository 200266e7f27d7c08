// A frame as a camera of a reference focal length would see it, so that the
// pixel lengths of acquisition and verification (distance-map truncation,
// sample spacing, shortest segment, the coverage score) are angles and one
// set of options decides alike for a 640 x 480 and a 5 megapixel camera.
//
// With s = f_ref / f_x, every pixel coordinate u becomes s u: the camera's
// K becomes diag(s, s, 1) K and its image s (width, height), each segment's
// end points s p and their covariances s^2 Sigma. The view is a pinhole
// camera like the frame's, so a pose aligned in it is the frame's pose, with
// the same covariance. Scaling a reference view again leaves it as it is.
#pragma once

#include <vector>

#include "common/messages/messages.h"

namespace lineloc {

struct ReferenceView {
  PinholeCamera camera;
  std::vector<ImageSegment> segments;
  // Reference pixels per pixel of the frame: s = f_ref / f_x.
  double scale = 1.0;
};

ReferenceView referenceView(const std::vector<ImageSegment>& segments, const PinholeCamera& camera,
                            double reference_focal_px);

}  // namespace lineloc
