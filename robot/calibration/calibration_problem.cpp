#include "robot/calibration/calibration_problem.h"

#include <cmath>

#include "common/camera/lens_distortion.h"

namespace lineloc {

CalibrationOptions openCvCompatibleOptions() {
  CalibrationOptions options;
  options.fix_skew = true;
  options.fix_aspect_ratio = true;
  options.aspect_ratio = 1.0;
  options.distortion_model = DistortionModel::kOpenCv5;
  return options;
}

std::vector<std::vector<Eigen::Vector2d>> reprojectionResiduals(const PlanarViews& views,
                                                                const CalibrationState& state) {
  const PinholeCamera& camera = state.calibration.camera;
  std::vector<std::vector<Eigen::Vector2d>> residuals(views.image_points.size());
  for (size_t view = 0; view < views.image_points.size(); ++view) {
    for (size_t i = 0; i < views.model_points.size(); ++i) {
      const Eigen::Vector3d p_camera =
          state.T_camera_model[view] *
          Eigen::Vector3d(views.model_points[i].x(), views.model_points[i].y(), 0.0);
      const Eigen::Vector2d distorted =
          distortNormalised(p_camera.hnormalized(), state.calibration.distortion);
      const Eigen::Vector2d predicted = camera.project(distorted.homogeneous());
      residuals[view].push_back(views.image_points[view][i] - predicted);
    }
  }
  return residuals;
}

double rmsError(const std::vector<Eigen::Vector2d>& residuals) {
  if (residuals.empty()) {
    return 0.0;
  }
  double squared = 0.0;
  for (const Eigen::Vector2d& r : residuals) {
    squared += r.squaredNorm();
  }
  return std::sqrt(squared / static_cast<double>(residuals.size()));
}

}  // namespace lineloc
