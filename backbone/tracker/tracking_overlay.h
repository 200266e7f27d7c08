// A picture of one tracked frame: the model lines projected with the frame's
// pose (green when aligned, orange when only predicted) over the image, and
// the image segments the front end found (red), so a user sees at a glance
// whether the model sits on the buildings.
#pragma once

#include <opencv2/core.hpp>
#include <vector>

#include "backbone/tracker/model_tracker.h"
#include "common/messages/messages.h"

namespace lineloc {

cv::Mat drawTrackingOverlay(const cv::Mat& image, const std::vector<ImageSegment>& segments,
                            const TrackedFrame& frame, const PinholeCamera& camera);

}  // namespace lineloc
