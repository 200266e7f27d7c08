#include "backbone/matching/reference_view.h"

#include <cmath>

namespace lineloc {

ReferenceView referenceView(const std::vector<ImageSegment>& segments, const PinholeCamera& camera,
                            double reference_focal_px) {
  ReferenceView view;
  view.scale = reference_focal_px / camera.fx;
  const double s = view.scale;
  view.camera = {s * camera.fx,
                 s * camera.fy,
                 s * camera.cx,
                 s * camera.cy,
                 s * camera.skew,
                 static_cast<int>(std::lround(s * camera.width)),
                 static_cast<int>(std::lround(s * camera.height))};
  view.segments = segments;
  const auto s_f = static_cast<float>(s);
  for (ImageSegment& segment : view.segments) {
    segment.start *= s_f;
    segment.end *= s_f;
    segment.start_covariance *= s_f * s_f;
    segment.end_covariance *= s_f * s_f;
  }
  return view;
}

}  // namespace lineloc
