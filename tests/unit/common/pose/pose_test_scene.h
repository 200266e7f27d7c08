// Synthetic scenes for pose tests, benchmarks and fuzzing: a 640x480 camera
// (f = 800 px) 6-10 m from a model of points and segments in a 4 m box (or on
// a tilted plane), with the true pose, measured features and isotropic
// Gaussian image noise.
#pragma once

#include <Eigen/Geometry>
#include <cstdint>
#include <random>

#include "common/pose/pose_problem.h"
#include "tests/support/pose_error.h"

namespace lineloc::test {

struct SceneOptions {
  int points = 0;
  int lines = 0;
  bool planar_points = false;
  // Standard deviation of the image noise per coordinate, pixels.
  double noise_px = 0.0;
  uint32_t seed = 1;
};

struct Scene {
  PoseProblem problem;
  Eigen::Isometry3d T_world_camera = Eigen::Isometry3d::Identity();
};

PinholeCamera testCamera();

// Every feature projects inside the image, in front of the camera. Measured
// covariances are noise_px^2 I (0.1^2 I when noise-free). Measured segment
// endpoints lie at random fractions inside the projected model segment.
Scene makeScene(const SceneOptions& options);

// The pose rotated by rotation_rad about a random axis and moved by
// translation_m in a random direction.
Eigen::Isometry3d perturbPose(const Eigen::Isometry3d& pose, double rotation_rad,
                              double translation_m, std::mt19937& random);

double rotationErrorRad(const Eigen::Isometry3d& estimate, const Eigen::Isometry3d& truth);
double translationErrorM(const Eigen::Isometry3d& estimate, const Eigen::Isometry3d& truth);

}  // namespace lineloc::test
