#include "tests/unit/common/pose/pose_test_scene.h"

namespace lineloc::test {

namespace {

Eigen::Vector3d randomUnit(std::mt19937& random) {
  std::normal_distribution<double> normal;
  return Eigen::Vector3d(normal(random), normal(random), normal(random)).normalized();
}

// Camera 6-10 m from the origin, looking at it, rolled at random.
Eigen::Isometry3d randomCameraPose(std::mt19937& random) {
  std::uniform_real_distribution<double> distance(6.0, 10.0);
  std::uniform_real_distribution<double> roll(-M_PI, M_PI);
  const Eigen::Vector3d centre = distance(random) * randomUnit(random);
  const Eigen::Vector3d forward = -centre.normalized();
  const Eigen::Vector3d helper =
      std::abs(forward.z()) < 0.9 ? Eigen::Vector3d::UnitZ() : Eigen::Vector3d::UnitX();
  const Eigen::Vector3d right = forward.cross(helper).normalized();
  Eigen::Matrix3d R_world_camera;
  R_world_camera << right, forward.cross(right), forward;
  Eigen::Isometry3d T_world_camera = Eigen::Isometry3d::Identity();
  T_world_camera.linear() =
      R_world_camera * Eigen::AngleAxisd(roll(random), Eigen::Vector3d::UnitZ());
  T_world_camera.translation() = centre;
  return T_world_camera;
}

bool isVisible(const PinholeCamera& camera, const Eigen::Isometry3d& T_camera_world,
               const Eigen::Vector3d& p_world) {
  const Eigen::Vector3d p_camera = T_camera_world * p_world;
  if (p_camera.z() < 0.5) {
    return false;
  }
  const Eigen::Vector2d pixel = camera.project(p_camera);
  return pixel.x() > 0.0 && pixel.x() < camera.width && pixel.y() > 0.0 &&
         pixel.y() < camera.height;
}

}  // namespace

PinholeCamera testCamera() {
  PinholeCamera camera;
  camera.fx = 800.0;
  camera.fy = 800.0;
  camera.cx = 320.0;
  camera.cy = 240.0;
  camera.width = 640;
  camera.height = 480;
  return camera;
}

Scene makeScene(const SceneOptions& options) {
  std::mt19937 random(options.seed);
  std::uniform_real_distribution<double> box(-2.0, 2.0);
  std::uniform_real_distribution<double> fraction(0.0, 0.3);
  std::uniform_real_distribution<double> length_m(0.5, 1.5);
  std::normal_distribution<double> noise(0.0, options.noise_px);
  Scene scene;
  scene.problem.camera = testCamera();
  scene.T_world_camera = randomCameraPose(random);
  const Eigen::Isometry3d T_camera_world = scene.T_world_camera.inverse();
  const PinholeCamera& camera = scene.problem.camera;
  const double sigma_px = options.noise_px > 0.0 ? options.noise_px : 0.1;
  const Eigen::Matrix2d covariance = sigma_px * sigma_px * Eigen::Matrix2d::Identity();
  const Eigen::Quaterniond plane_rotation(Eigen::AngleAxisd(0.6, randomUnit(random)));
  const auto noisy = [&](const Eigen::Vector2d& pixel) {
    return Eigen::Vector2d(pixel.x() + noise(random), pixel.y() + noise(random));
  };
  while (static_cast<int>(scene.problem.points.size()) < options.points) {
    Eigen::Vector3d p_world(box(random), box(random), box(random));
    if (options.planar_points) {
      p_world = plane_rotation * Eigen::Vector3d(p_world.x(), p_world.y(), 0.0);
    }
    if (isVisible(camera, T_camera_world, p_world)) {
      scene.problem.points.push_back(
          {p_world, noisy(camera.project(T_camera_world * p_world)), covariance});
    }
  }
  while (static_cast<int>(scene.problem.lines.size()) < options.lines) {
    const Eigen::Vector3d start(box(random), box(random), box(random));
    const Eigen::Vector3d end = start + length_m(random) * randomUnit(random);
    if (!isVisible(camera, T_camera_world, start) || !isVisible(camera, T_camera_world, end)) {
      continue;
    }
    const Eigen::Vector3d seen_start = start + fraction(random) * (end - start);
    const Eigen::Vector3d seen_end = end + fraction(random) * (start - end);
    scene.problem.lines.push_back({start, end, noisy(camera.project(T_camera_world * seen_start)),
                                   noisy(camera.project(T_camera_world * seen_end)), covariance,
                                   covariance});
  }
  return scene;
}

Eigen::Isometry3d perturbPose(const Eigen::Isometry3d& pose, double rotation_rad,
                              double translation_m, std::mt19937& random) {
  Eigen::Isometry3d perturbed = pose;
  perturbed.linear() = Eigen::AngleAxisd(rotation_rad, randomUnit(random)) * pose.linear();
  perturbed.translation() += translation_m * randomUnit(random);
  return perturbed;
}

double rotationErrorRad(const Eigen::Isometry3d& estimate, const Eigen::Isometry3d& truth) {
  return Eigen::AngleAxisd(estimate.linear().transpose() * truth.linear()).angle();
}

double translationErrorM(const Eigen::Isometry3d& estimate, const Eigen::Isometry3d& truth) {
  return (estimate.translation() - truth.translation()).norm();
}

}  // namespace lineloc::test
