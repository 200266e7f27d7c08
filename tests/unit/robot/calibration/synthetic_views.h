// Synthetic views of a 9x6 planar grid by a known camera, for calibration tests.
#pragma once

#include <Eigen/Geometry>
#include <cmath>
#include <random>
#include <vector>

#include "common/camera/lens_distortion.h"
#include "robot/calibration/calibration_problem.h"

namespace lineloc::testing {

struct SyntheticViews {
  CalibrationState truth;
  PlanarViews views;
};

// A 640x480 camera whose parameters obey `options` (zero skew, fx / fy, centred
// principal point, distortion model), looking at the grid from `view_count`
// directions, tilted by up to 0.6 rad, with i.i.d. Gaussian pixel noise.
inline SyntheticViews makeSyntheticViews(int view_count, const CalibrationOptions& options,
                                         double noise_sigma_px, unsigned seed) {
  SyntheticViews synthetic;
  PlanarViews& views = synthetic.views;
  views.image_width = 640;
  views.image_height = 480;
  for (int row = 0; row < 6; ++row) {
    for (int col = 0; col < 9; ++col) {
      views.model_points.emplace_back(0.04 * col, 0.04 * row);
    }
  }
  PinholeCamera& camera = synthetic.truth.calibration.camera;
  camera = {810.0, 790.0, 331.0, 247.0, options.fix_skew ? 0.0 : 0.4, 640, 480};
  if (options.fix_aspect_ratio) {
    camera.fy = camera.fx / options.aspect_ratio;
  }
  if (options.fix_principal_point) {
    camera.cx = 319.5;
    camera.cy = 239.5;
  }
  synthetic.truth.calibration.distortion =
      options.distortion_model == DistortionModel::kRadialK1K2
          ? std::vector<double>{-0.25, 0.12, 0.0, 0.0, 0.0}
          : std::vector<double>{-0.25, 0.12, 0.0012, -0.0007, -0.03};

  std::mt19937 random(seed);
  std::normal_distribution<double> standard_normal(0.0, 1.0);
  const auto noise = [&](std::mt19937& r) { return noise_sigma_px * standard_normal(r); };
  const Eigen::Vector3d board_centre(0.16, 0.10, 0.0);
  for (int view = 0; view < view_count; ++view) {
    const double direction = 2.0 * M_PI * view / view_count;
    const double tilt = 0.25 + 0.35 * ((view % 3) / 2.0);
    const Eigen::Matrix3d R =
        Eigen::AngleAxisd(tilt, Eigen::Vector3d(std::cos(direction), std::sin(direction), 0.0))
            .toRotationMatrix() *
        Eigen::AngleAxisd(0.1 * view, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    const Eigen::Vector3d centre_in_camera(0.08 * std::cos(3.0 * direction),
                                           0.06 * std::sin(2.0 * direction), 0.55 + 0.02 * view);
    Eigen::Isometry3d T_camera_model = Eigen::Isometry3d::Identity();
    T_camera_model.linear() = R;
    T_camera_model.translation() = centre_in_camera - R * board_centre;
    synthetic.truth.T_camera_model.push_back(T_camera_model);
    std::vector<Eigen::Vector2d> image_points;
    for (const Eigen::Vector2d& M : views.model_points) {
      const Eigen::Vector2d x = (T_camera_model * Eigen::Vector3d(M.x(), M.y(), 0.0)).hnormalized();
      const Eigen::Vector2d distorted =
          distortNormalised(x, synthetic.truth.calibration.distortion);
      image_points.push_back(camera.project(distorted.homogeneous()) +
                             Eigen::Vector2d(noise(random), noise(random)));
    }
    views.image_points.push_back(image_points);
  }
  return synthetic;
}

// Two zero-skew views tilted about different axes (two tilted about one axis
// are degenerate even with zero skew).
inline SyntheticViews makeTwoViewsWithZeroSkew() {
  CalibrationOptions options;
  options.fix_skew = true;
  SyntheticViews synthetic = makeSyntheticViews(3, options, 0.0, 1);
  synthetic.views.image_points.pop_back();
  synthetic.truth.T_camera_model.pop_back();
  return synthetic;
}

// The homography H = K [r1 r2 t] of a view without distortion.
inline Eigen::Matrix3d viewHomography(const PinholeCamera& camera,
                                      const Eigen::Isometry3d& T_camera_model) {
  Eigen::Matrix3d Rt;
  Rt << T_camera_model.linear().col(0), T_camera_model.linear().col(1),
      T_camera_model.translation();
  return camera.K() * Rt;
}

}  // namespace lineloc::testing
