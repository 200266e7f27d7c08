// The robot's vision front end (Persa & Jonker §3): each camera frame becomes
// a small set of straight line segments and Förstner corners in undistorted
// pixel coordinates, with their uncertainty, ready for the LineSet.
//
// Pipeline: grey conversion (colour input) -> the image's noise
// (edges/noise_estimate.h), which sets the edge threshold and the contrast a
// segment needs -> sub-pixel edges
// (edges/edge_detector.h) -> chains (edges/edge_linker.h) -> undistortion
// lookup, split-and-merge, TLS refit, gap merge, a contrario validation,
// corner snapping (lines/line_extractor.h); Förstner corners on the same gradients
// (corners/forstner_detector.h), undistorted through the same table with
// their covariance carried by its Jacobian: Sigma_u = J Sigma J^T. Where a
// corner is also a junction of two fitted lines (within junction_radius),
// it takes the junction's position and covariance: the lines' intersection
// is free of the bias blur gives the gradient-line intersection at a corner
// tip, and rests on many more pixels.
// Every buffer is kept between frames: no allocation in steady state.
#pragma once

#include <opencv2/core.hpp>
#include <vector>

#include "common/camera/camera_calibration.h"
#include "common/messages/messages.h"
#include "common/parallel/helper_thread.h"
#include "robot/vision/corners/forstner_detector.h"
#include "robot/vision/edges/edge_detector.h"
#include "robot/vision/edges/edge_linker.h"
#include "robot/vision/edges/noise_estimate.h"
#include "robot/vision/edges/undistortion_table.h"
#include "robot/vision/lines/line_extractor.h"

namespace lineloc {

struct FeatureExtractorOptions {
  EdgeDetectorOptions edges;
  EdgeLinkerOptions linking;
  LineExtractorOptions lines;
  ForstnerOptions corners;
  bool detect_corners = true;
  // The corners on a thread of their own beside the linking and line
  // fitting, which take longer: a frame's features then cost the edges and
  // the lines on a machine with a core to spare. false: one thread, the
  // corners taking each gradient row as it comes. Both give the same corners.
  bool corners_on_own_thread = true;
  double junction_radius_px = 3.0;
};

// The options of a front end for model-based tracking, the robot's: the
// defaults with the edge threshold's floor lowered to 4 grey levels per
// pixel, which keeps the steps down to about 12 grey levels where walls in
// shade meet each other and the street (robot_agent.h gives why); the
// defaults keep the steps of about 24 and over.
FeatureExtractorOptions trackingFrontEndOptions();

// Fit quality of segments[i], beyond what ImageSegment carries.
struct SegmentFitQuality {
  float sigma_offset_px;  // normal offset at the centroid
  float sigma_angle_rad;
  int point_count;
};

struct FrameFeatures {
  std::vector<ImageSegment> segments;              // undistorted pixels, longest first
  std::vector<SegmentFitQuality> segment_quality;  // parallel to segments
  std::vector<ImageCorner> corners;                // undistorted pixels, strongest first
  double noise_sigma = 0.0;                        // the image's, grey levels
  int rejected_segments = 0;                       // by the a contrario test or min_contrast
};

class FeatureExtractor : private GradientRowListener {
 public:
  static constexpr int kMinImageSidePx = 16;
  static constexpr int kMaxImageSidePx = 8192;

  // Throws std::invalid_argument for a calibration size outside
  // [kMinImageSidePx, kMaxImageSidePx] or out-of-range options.
  explicit FeatureExtractor(const CameraCalibration& calibration,
                            const FeatureExtractorOptions& options = {});

  // `image`: 8-bit grey, BGR or BGRA of the calibration's size. Throws
  // std::invalid_argument naming the problem for any other image. A blank or
  // saturated frame yields empty sets. The result stays valid until the next call.
  const FrameFeatures& extract(const cv::Mat& image);

 private:
  // On one thread, the Förstner operator takes each gradient row as it comes.
  void gradientRow(int y, const cv::Mat& gradient_x, const cv::Mat& gradient_y) override;
  void detectCorners();
  void fitLines();
  const cv::Mat& toGrey(const cv::Mat& image);
  void exportSegments();
  void exportCorners();
  const Junction* nearestJunction(const Eigen::Vector2f& position) const;

  CameraCalibration calibration_;
  FeatureExtractorOptions options_;
  UndistortionTable undistortion_;
  EdgeDetector edge_detector_;
  EdgeLinker linker_;
  NoiseEstimator noise_estimator_;
  LineExtractor line_extractor_;
  ForstnerDetector corner_detector_;
  HelperThread corner_thread_;
  cv::Mat grey_;
  std::vector<Junction> junctions_by_x_;  // the line extractor's, sorted by x
  FrameFeatures features_;
};

}  // namespace lineloc
