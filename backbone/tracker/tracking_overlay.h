// A picture of one tracked frame: the model lines projected with the frame's
// pose (green when aligned, orange when only predicted), the image segments
// the front end found (red) and its corners (yellow rings, filled cyan where
// the alignment used them), over the image undistorted with the calibration —
// segments and projections live in undistorted pixels — so a user sees at a
// glance whether the model sits on the buildings.
#pragma once

#include <opencv2/core.hpp>
#include <vector>

#include "backbone/tracker/model_tracker.h"
#include "common/camera/camera_calibration.h"
#include "common/messages/messages.h"

namespace lineloc {

cv::Mat drawTrackingOverlay(const cv::Mat& image, const std::vector<ImageSegment>& segments,
                            const std::vector<ImageCorner>& corners, const TrackedFrame& frame,
                            const CameraCalibration& calibration);

}  // namespace lineloc
