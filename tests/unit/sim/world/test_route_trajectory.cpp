#include <gtest/gtest.h>

#include "sim/sensors/sensor_synthesis.h"
#include "sim/world/route_trajectory.h"

namespace lineloc {
namespace {

// An L-shaped street route with a sharp corner and a gentle bend.
std::vector<Eigen::Vector2d> lRoute() {
  return {{0, 0}, {60, 0}, {60, 40}, {90, 70}};
}

std::function<double(const Eigen::Vector2d&)> flat(double z_m) {
  return [z_m](const Eigen::Vector2d&) { return z_m; };
}

// Rolling ground climbing northwards: grades up to 13 %.
double hills(const Eigen::Vector2d& xy) {
  return 2.0 * std::sin(0.05 * xy.x()) + 0.03 * xy.y();
}

RouteDriveOptions testDrive() {
  RouteDriveOptions options;
  options.duration_s = 60.0;
  options.seed = 3;
  return options;
}

TEST(RouteTrajectory, FollowsTheRouteWithinTheSplineCornerCut) {
  const RouteTrajectory trajectory(lRoute(), flat(0.5), testDrive());
  // A uniform cubic B-spline cuts a 90-degree corner by at most ~ spacing / 3.
  const double allowed_m = testDrive().control_spacing_m / 3.0 + 1e-6;
  const auto route = lRoute();
  for (int64_t t = trajectory.startStamp_ns(); t <= trajectory.endStamp_ns(); t += 100'000'000) {
    const sim::TruthSample sample = trajectory.at(t);
    double distance = 1e9;
    for (size_t i = 1; i < route.size(); ++i) {
      const Eigen::Vector2d ab = route[i] - route[i - 1];
      const Eigen::Vector2d p = sample.p_world_body.head<2>();
      const double s = std::clamp((p - route[i - 1]).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
      distance = std::min(distance, (p - route[i - 1] - s * ab).norm());
    }
    ASSERT_LE(distance, allowed_m) << "at " << (t - trajectory.startStamp_ns()) * 1e-9 << " s";
    EXPECT_NEAR(sample.p_world_body.z(), 0.8, 1e-12);
    const double speed = sample.v_world_body.norm();
    EXPECT_LE(speed, testDrive().max_speed_m_s + 1e-9);
  }
  // Still during the alignment period.
  EXPECT_EQ(trajectory.at(trajectory.startStamp_ns() + 4'000'000'000).v_world_body.norm(), 0.0);
}

// Flat ground, and hills whose grade the robot pitches with.
class RouteTrajectoryOnGround
    : public ::testing::TestWithParam<std::function<double(const Eigen::Vector2d&)>> {};

TEST_P(RouteTrajectoryOnGround, VelocityAccelerationAndRateAreDerivatives) {
  const RouteTrajectory trajectory(lRoute(), GetParam(), testDrive());
  constexpr int64_t kStep_ns = 1'000'000;  // central differences over 1 ms
  for (double t_s = 6.0; t_s < 59.0; t_s += 1.7) {
    const int64_t t = trajectory.startStamp_ns() + static_cast<int64_t>(t_s * 1e9);
    const sim::TruthSample before = trajectory.at(t - kStep_ns);
    const sim::TruthSample now = trajectory.at(t);
    const sim::TruthSample after = trajectory.at(t + kStep_ns);
    const Eigen::Vector3d velocity = (after.p_world_body - before.p_world_body) / 2e-3;
    const Eigen::Vector3d acceleration =
        (after.p_world_body - 2.0 * now.p_world_body + before.p_world_body) / 1e-6;
    // Central-difference truncation h^2/6 p''' ~ 1e-7 m/s; the second
    // difference amplifies the ~1e-12 m arclength inversion error by 1/h^2.
    EXPECT_NEAR((velocity - now.v_world_body).norm(), 0.0, 1e-5) << t_s;
    EXPECT_NEAR((acceleration - now.a_world_body).norm(), 0.0, 5e-3) << t_s;
    // omega_body = 2 vec(q(t - h)^-1 q(t + h)) / (2 h), to O(h^2).
    const Eigen::Quaterniond turn = before.q_world_body.conjugate() * after.q_world_body;
    EXPECT_NEAR((turn.vec() / 1e-3 - now.gyro_body_radps).norm(), 0.0, 1e-4) << t_s;
    // The body's x axis lies along the velocity: it pitches with the grade.
    if (now.v_world_body.norm() > 0.1) {
      EXPECT_GT((now.q_world_body * Eigen::Vector3d::UnitX()).dot(now.v_world_body.normalized()),
                1.0 - 1e-9)
          << t_s;
    }
  }
}

TEST_P(RouteTrajectoryOnGround, IntegratingNoiselessImuReproducesTheTrajectory) {
  const RouteTrajectory trajectory(lRoute(), GetParam(), testDrive());
  sim::ImuModel model;
  model.noise = false;
  const std::vector<sim::SimImuSample> imu = sim::synthesiseImu(trajectory, model, 1);
  ASSERT_GT(imu.size(), 11000u);
  const sim::TruthSample start = trajectory.at(imu.front().stamp_ns);
  Eigen::Quaterniond q = start.q_world_body;
  Eigen::Vector3d v = start.v_world_body;
  Eigen::Vector3d p = start.p_world_body;
  const Eigen::Vector3d gravity(0.0, 0.0, -testDrive().gravity_m_s2);
  double max_position_error = 0.0;
  for (size_t k = 1; k < imu.size(); ++k) {
    const double dt = static_cast<double>(imu[k].stamp_ns - imu[k - 1].stamp_ns) * 1e-9;
    // Trapezoidal strapdown: mean rate over the step, acceleration at both ends.
    const Eigen::Vector3d a0 = q * imu[k - 1].accel_mps2 + gravity;
    const Eigen::Vector3d rotation = 0.5 * (imu[k - 1].gyro_radps + imu[k].gyro_radps) * dt;
    if (rotation.norm() > 0.0) {
      q = q * Eigen::Quaterniond(Eigen::AngleAxisd(rotation.norm(), rotation.normalized()));
    }
    const Eigen::Vector3d a1 = q * imu[k].accel_mps2 + gravity;
    p += v * dt + (a0 / 3.0 + a1 / 6.0) * dt * dt;
    v += 0.5 * (a0 + a1) * dt;
    const sim::TruthSample truth = trajectory.at(imu[k].stamp_ns);
    max_position_error = std::max(max_position_error, (p - truth.p_world_body).norm());
  }
  const sim::TruthSample end = trajectory.at(imu.back().stamp_ns);
  // The trapezoid errs by ~ dt^2 / 12 |f''| per unit time: with yaw
  // accelerations' rates |w''| < 0.5 rad/s^3 over 60 s, ~6e-6 rad of yaw;
  // with |a''| < 0.5 m/s^4, ~6e-5 m/s in velocity and under 1e-4 m in
  // position (the run gives ~1e-6 m and ~3e-7 rad).
  EXPECT_LT(max_position_error, 1e-4);
  EXPECT_LT((v - end.v_world_body).norm(), 6e-5);
  EXPECT_LT(q.angularDistance(end.q_world_body), 1e-5);
}

INSTANTIATE_TEST_SUITE_P(Grounds, RouteTrajectoryOnGround, ::testing::Values(flat(0.0), hills),
                         [](const auto& info) { return info.index == 0 ? "Flat" : "Hills"; });

TEST(RouteTrajectory, RidesTheGroundItIsGiven) {
  const RouteTrajectory trajectory(lRoute(), hills, testDrive());
  double most_off_m = 0.0;
  double most_off_along_legs_m = 0.0;
  for (int64_t t = trajectory.startStamp_ns(); t <= trajectory.endStamp_ns(); t += 50'000'000) {
    const sim::TruthSample sample = trajectory.at(t);
    const Eigen::Vector2d xy = sample.p_world_body.head<2>();
    const double off_m = std::abs(sample.p_world_body.z() - testDrive().body_height_m - hills(xy));
    most_off_m = std::max(most_off_m, off_m);
    if ((xy - Eigen::Vector2d(60, 0)).norm() > 10.0 &&
        (xy - Eigen::Vector2d(60, 40)).norm() > 10.0) {
      most_off_along_legs_m = std::max(most_off_along_legs_m, off_m);
    }
  }
  // Along a straight leg the cubic through heights d <= 5 m apart errs by
  // (5 / 384) d^4 |h''''| < 1e-4 m; round the first corner the grade breaks
  // from dh/dx = 0.1 cos 3 to dh/dy = 0.03, which a cubic over one span
  // follows to |dh'| d / 8 = 0.08 m.
  EXPECT_LT(most_off_along_legs_m, 1e-3);
  EXPECT_LT(most_off_m, std::abs(0.03 - 0.1 * std::cos(3.0)) * 5.0 / 8.0);
}

TEST(RouteTrajectory, StopsAtTheEndOfAShortRoute) {
  RouteDriveOptions options = testDrive();
  options.duration_s = 120.0;
  const RouteTrajectory trajectory({{0, 0}, {40, 0}}, flat(0.0), options);
  const sim::TruthSample start = trajectory.at(trajectory.startStamp_ns());
  const sim::TruthSample end = trajectory.at(trajectory.endStamp_ns());
  EXPECT_NEAR(end.v_world_body.norm(), 0.0, 1e-9);
  ASSERT_TRUE(end.q_world_body.coeffs().allFinite());
  // It stops where the road ends (the planner brakes to reach it exactly).
  EXPECT_NEAR(end.p_world_body.x() - start.p_world_body.x(), trajectory.pathLength(), 0.05);
  EXPECT_LE(end.p_world_body.x(), 40.0 + 1e-6);
}

// The turn back of street_route.h with a 3 m radius: a diagonal onto a half
// circle centred 3 m ahead, then back 6 m to the side of the way it came.
TEST(RouteTrajectory, TurnsBackWithinItsLateralAccelerationLimit) {
  std::vector<Eigen::Vector2d> route{{0, 0}, {40, 0}, {43, 3}};
  for (int step = 1; step <= 8; ++step) {
    const double turned = M_PI * step / 8;
    route.emplace_back(43.0 + 3.0 * std::sin(turned), 3.0 * std::cos(turned));
  }
  route.emplace_back(0, -3);
  RouteDriveOptions options = testDrive();
  options.stop_probability = 0.0;
  options.duration_s = 200.0;  // longer than the route takes: it ends at its end
  const RouteTrajectory trajectory(route, flat(0.0), options);
  double most_lateral = 0.0;
  for (int64_t t = trajectory.startStamp_ns(); t <= trajectory.endStamp_ns(); t += 20'000'000) {
    const sim::TruthSample sample = trajectory.at(t);
    ASSERT_TRUE(sample.q_world_body.coeffs().allFinite());
    const double speed = sample.v_world_body.norm();
    if (speed < 1e-6) {
      continue;
    }
    const Eigen::Vector3d along = sample.v_world_body / speed;
    const Eigen::Vector3d lateral = sample.a_world_body - sample.a_world_body.dot(along) * along;
    most_lateral = std::max(most_lateral, lateral.norm());
  }
  EXPECT_LE(most_lateral, options.max_lateral_acceleration_m_s2 + 1e-6);
  // It has driven round and back along y = -3, facing -x.
  const sim::TruthSample end = trajectory.at(trajectory.endStamp_ns());
  EXPECT_LT(end.p_world_body.x(), 2.0);
  EXPECT_NEAR(end.p_world_body.y(), -3.0, 0.1);
  EXPECT_LT((end.q_world_body * Eigen::Vector3d::UnitX()).x(), -0.99);
}

TEST(RouteTrajectory, StartsMovingAtTheInitialSpeed) {
  RouteDriveOptions options = testDrive();
  options.initial_still_s = 0.0;
  options.initial_speed_m_s = 1.5;
  const RouteTrajectory trajectory(lRoute(), flat(0.0), options);
  const sim::TruthSample start = trajectory.at(trajectory.startStamp_ns());
  EXPECT_NEAR((start.v_world_body - Eigen::Vector3d(1.5, 0.0, 0.0)).norm(), 0.0, 1e-9);
  // Position, velocity and acceleration agree from the first instant on.
  constexpr int64_t kStep_ns = 1'000'000;
  for (int64_t t = trajectory.startStamp_ns() + kStep_ns;
       t < trajectory.startStamp_ns() + 5'000'000'000; t += 500'000'000) {
    const Eigen::Vector3d velocity =
        (trajectory.at(t + kStep_ns).p_world_body - trajectory.at(t - kStep_ns).p_world_body) /
        2e-3;
    EXPECT_NEAR((velocity - trajectory.at(t).v_world_body).norm(), 0.0, 1e-5);
    EXPECT_GT(trajectory.at(t).v_world_body.norm(), options.min_speed_m_s - 1e-9);
  }
  // It stops where the road ends, as a standing start does.
  options.duration_s = 200.0;
  const RouteTrajectory to_the_end(lRoute(), flat(0.0), options);
  EXPECT_NEAR(to_the_end.at(to_the_end.endStamp_ns()).v_world_body.norm(), 0.0, 1e-9);
  EXPECT_NEAR(
      (to_the_end.at(to_the_end.endStamp_ns()).p_world_body.head<2>() - Eigen::Vector2d(90, 70))
          .norm(),
      0.0, testDrive().control_spacing_m);
}

TEST(RouteTrajectory, RejectsAMovingStartThatStandsStillOrExceedsTheTopSpeed) {
  RouteDriveOptions options = testDrive();
  options.initial_speed_m_s = 1.0;
  options.initial_still_s = 5.0;
  EXPECT_THROW(RouteTrajectory(lRoute(), flat(0.0), options), std::invalid_argument);
  options.initial_still_s = 0.0;
  options.initial_speed_m_s = options.max_speed_m_s + 0.1;
  EXPECT_THROW(RouteTrajectory(lRoute(), flat(0.0), options), std::invalid_argument);
}

TEST(RouteTrajectory, RejectsDegenerateRoutes) {
  EXPECT_THROW(RouteTrajectory({{0, 0}}, flat(0.0), testDrive()), std::invalid_argument);
  EXPECT_THROW(RouteTrajectory({{0, 0}, {1, 0}}, flat(0.0), testDrive()), std::invalid_argument);
}

}  // namespace
}  // namespace lineloc
