#include "robot/calibration/calibration_file.h"

#include <ceres/rotation.h>
#include <fmt/format.h>

#include <filesystem>
#include <opencv2/core.hpp>
#include <stdexcept>

namespace lineloc {

namespace {

cv::Mat column(const std::vector<double>& values) {
  return cv::Mat(values, true);
}

template <int N>
cv::Mat row(const Eigen::Matrix<double, N, 1>& values) {
  return cv::Mat(1, N, CV_64F, const_cast<double*>(values.data())).clone();
}

// One row per view: rotation vector (OpenCV's rvec) then translation (tvec), metres.
cv::Mat extrinsicRows(const std::vector<Eigen::Isometry3d>& T_camera_model) {
  cv::Mat rows(static_cast<int>(T_camera_model.size()), 6, CV_64F);
  for (size_t view = 0; view < T_camera_model.size(); ++view) {
    const Eigen::Matrix3d R = T_camera_model[view].linear();
    double* out = rows.ptr<double>(static_cast<int>(view));
    ceres::RotationMatrixToAngleAxis(ceres::ColumnMajorAdapter3x3(R.data()), out);
    Eigen::Map<Eigen::Vector3d>(out + 3) = T_camera_model[view].translation();
  }
  return rows;
}

cv::Mat poseStdDevRows(const std::vector<Eigen::Matrix<double, 6, 1>>& pose_std_dev) {
  cv::Mat rows;
  for (const Eigen::Matrix<double, 6, 1>& std_dev : pose_std_dev) {
    rows.push_back(row<6>(std_dev));
  }
  return rows;
}

void writeStrings(cv::FileStorage& storage, const std::string& key,
                  const std::vector<std::string>& values) {
  storage << key << "[";
  for (const std::string& value : values) {
    storage << value;
  }
  storage << "]";
}

const char* distortionModelName(DistortionModel model) {
  return model == DistortionModel::kRadialK1K2 ? "k1k2" : "opencv5";
}

}  // namespace

void writeCalibrationFile(const std::string& path, const CalibrationResult& result,
                          const CalibrationOptions& options,
                          const std::vector<std::string>& view_names) {
  const std::string temporary_path = path + ".partial";
  {
    cv::FileStorage storage = openCalibrationFileForWriting(temporary_path);
    storage << "nr_of_frames" << static_cast<int>(result.state.T_camera_model.size());
    writeCameraCalibration(storage, result.state.calibration);
    storage << "fix_skew" << static_cast<int>(options.fix_skew);
    storage << "fix_aspect_ratio" << static_cast<int>(options.fix_aspect_ratio);
    storage << "fix_principal_point" << static_cast<int>(options.fix_principal_point);
    storage << "distortion_model" << distortionModelName(options.distortion_model);
    storage << "avg_reprojection_error" << result.rms_error_px;
    storage << "per_view_reprojection_errors" << column(result.per_view_rms_error_px);
    storage << "extrinsic_parameters" << extrinsicRows(result.state.T_camera_model);
    if (result.uncertainty.available) {
      storage << "estimated_noise_px" << result.uncertainty.noise_sigma_px;
      storage << "camera_matrix_std_dev" << row<5>(result.uncertainty.intrinsics_std_dev);
      storage << "distortion_coefficients_std_dev" << row<5>(result.uncertainty.distortion_std_dev);
      storage << "extrinsic_parameters_std_dev" << poseStdDevRows(result.uncertainty.pose_std_dev);
    }
    writeStrings(storage, "view_names", view_names);
    writeStrings(storage, "warnings", result.warnings);
  }
  std::error_code error;
  std::filesystem::rename(temporary_path, path, error);
  if (error) {
    std::filesystem::remove(temporary_path);
    throw std::runtime_error(fmt::format("cannot write '{}': {}", path, error.message()));
  }
}

}  // namespace lineloc
