// The library a user would pick instead: cv::calibrateCamera on the very same
// views, with the flags that match lineloc's OpenCV-compatible options (zero
// skew, fx / fy fixed at 1, five distortion coefficients).
#pragma once

#include <opencv2/calib3d.hpp>
#include <vector>

#include "robot/calibration/calibration_problem.h"

namespace lineloc::testing {

struct OpenCvCalibration {
  double rms_px = 0.0;  // as cv::calibrateCamera reports it
  cv::Mat camera_matrix;
  cv::Mat distortion;
  std::vector<cv::Mat> rvecs;
  std::vector<cv::Mat> tvecs;
};

struct OpenCvViews {
  std::vector<std::vector<cv::Point3f>> object_points;
  std::vector<std::vector<cv::Point2f>> image_points;
  cv::Size image_size;
};

inline OpenCvViews toOpenCv(const PlanarViews& views) {
  OpenCvViews converted;
  converted.image_size = cv::Size(views.image_width, views.image_height);
  std::vector<cv::Point3f> model;
  for (const Eigen::Vector2d& M : views.model_points) {
    model.emplace_back(static_cast<float>(M.x()), static_cast<float>(M.y()), 0.0f);
  }
  for (const std::vector<Eigen::Vector2d>& points : views.image_points) {
    converted.object_points.push_back(model);
    std::vector<cv::Point2f>& image = converted.image_points.emplace_back();
    for (const Eigen::Vector2d& m : points) {
      image.emplace_back(static_cast<float>(m.x()), static_cast<float>(m.y()));
    }
  }
  return converted;
}

// cv::calibrateCamera with CALIB_FIX_ASPECT_RATIO from an identity start (so
// fx = fy), as OpenCV's sample produced left_intrinsics.yml.
inline OpenCvCalibration calibrateWithOpenCv(const OpenCvViews& views) {
  OpenCvCalibration result;
  result.camera_matrix = cv::Mat::eye(3, 3, CV_64F);
  result.rms_px = cv::calibrateCamera(views.object_points, views.image_points, views.image_size,
                                      result.camera_matrix, result.distortion, result.rvecs,
                                      result.tvecs, cv::CALIB_FIX_ASPECT_RATIO);
  return result;
}

// OpenCV's solution as a lineloc state, to evaluate both with one cost function.
inline CalibrationState stateOf(const OpenCvCalibration& opencv, const PlanarViews& views) {
  CalibrationState state;
  const cv::Mat& K = opencv.camera_matrix;
  state.calibration.camera = {K.at<double>(0, 0), K.at<double>(1, 1), K.at<double>(0, 2),
                              K.at<double>(1, 2), K.at<double>(0, 1), views.image_width,
                              views.image_height};
  state.calibration.distortion.assign(opencv.distortion.begin<double>(),
                                      opencv.distortion.end<double>());
  for (size_t view = 0; view < opencv.rvecs.size(); ++view) {
    cv::Matx33d R;
    cv::Rodrigues(opencv.rvecs[view], R);
    Eigen::Isometry3d T_camera_model = Eigen::Isometry3d::Identity();
    for (int row = 0; row < 3; ++row) {
      for (int col = 0; col < 3; ++col) {
        T_camera_model.linear()(row, col) = R(row, col);
      }
      T_camera_model.translation()(row) = opencv.tvecs[view].at<double>(row);
    }
    state.T_camera_model.push_back(T_camera_model);
  }
  return state;
}

}  // namespace lineloc::testing
