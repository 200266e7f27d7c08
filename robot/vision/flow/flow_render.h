// Pictures of a flow field for the user: the Middlebury colour coding (Baker
// et al., IJCV 2011: hue = direction on a 55-colour wheel, saturation =
// magnitude / largest magnitude) beside the first frame with one arrow per
// moving block, drawn block side / largest magnitude times the flow.
#pragma once

#include <opencv2/core.hpp>

#include "robot/vision/flow/correlation_flow.h"

namespace lineloc {

// BGR, twice the frame's width: colour code (unknown flow black) | arrows.
cv::Mat renderFlow(const FlowField& field, const cv::Mat& first_frame);

// The colour code alone: CV_8UC3 for `flow_px` (CV_32FC2), black where
// `known` is zero; magnitudes scaled by `max_magnitude_px` (> 0).
cv::Mat flowColourCode(const cv::Mat& flow_px, const cv::Mat& known, double max_magnitude_px);

}  // namespace lineloc
