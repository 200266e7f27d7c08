// What lineloc-features does: the robot's front end (feature_extractor.h) on
// one image, and what the robot would send from it: the segments and corners
// as text (feature_report.h), an overlay on the undistorted image, and the
// frame's noise level with the segments that noise explained.
#pragma once

#include <iosfwd>
#include <string>

#include "robot/vision/features/feature_extractor.h"

namespace lineloc {

struct FeaturesToolConfig {
  // 8-bit grey or colour image file.
  std::string image;
  // OpenCV YAML layout; empty: an ideal camera of the image's size (focal
  // length its larger side, principal point its centre, no distortion).
  std::string camera_calibration;
  // Overlay image written; empty: none.
  std::string out;
  FeatureExtractorOptions extractor = trackingFrontEndOptions();
};

struct FeaturesToolSummary {
  double noise_sigma = 0.0;
  size_t segments = 0;
  int rejected_segments = 0;
  size_t corners = 0;
};

// Writes the features as text to `out`, and the overlay. Throws
// std::runtime_error naming the file that cannot be read or written.
FeaturesToolSummary runFeaturesTool(const FeaturesToolConfig& config, std::ostream& out);

}  // namespace lineloc
