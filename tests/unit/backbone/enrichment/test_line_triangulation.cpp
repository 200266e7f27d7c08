// A façade detail line (a window's top edge on a wall) seen by a camera
// driving down the street: its triangulation from noisy segments lies within
// its covariance of the truth, in the wall when constrained to it, over the
// stretch two views see; too few views, too short a baseline, a segment of
// no length, views whose planes coincide and a view that saw another line are
// refused.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <vector>

#include "backbone/enrichment/line_triangulation.h"

namespace lineloc {
namespace {

const PinholeCamera kCamera{500, 500, 320, 240, 0, 640, 480};
// The wall x = 10 m; a window's side, vertical at y = 5 m from 2 to 3.5 m
// height, and its top edge at 3.5 m height from y = 4 to 5 m, parallel to the
// street the camera drives down.
const Eigen::Vector3d kEdgeStart(10.0, 5.0, 2.0);
const Eigen::Vector3d kEdgeEnd(10.0, 5.0, 3.5);
const Eigen::Vector3d kTopStart(10.0, 4.0, 3.5);
const Eigen::Vector3d kTopEnd(10.0, 5.0, 3.5);
constexpr double kPixelSigma = 0.5;
// chi^2_2(0.9973): across the line, the error has two dimensions.
constexpr double kChi2TwoDof = 11.83;

// The camera at (0, y, 1.6) looking along +x, turned `yaw_rad` about z.
Eigen::Isometry3d cameraAt(double y, double yaw_rad = 0.0) {
  Eigen::Matrix3d R_world_camera;
  R_world_camera << 0, 0, 1, -1, 0, 0, 0, -1, 0;  // camera z along +x, image y down
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() = Eigen::AngleAxisd(yaw_rad, Eigen::Vector3d::UnitZ()) * R_world_camera;
  pose.translation() = Eigen::Vector3d(0.0, y, 1.6);
  return pose;
}

Eigen::Vector2d project(const Eigen::Isometry3d& T_world_camera, const Eigen::Vector3d& p) {
  return kCamera.project(T_world_camera.inverse() * p);
}

// The view of the edge's stretch [from, to] (fractions along it) from
// `T_world_camera`, its endpoints moved by pixel noise.
LineObservation view(const Eigen::Isometry3d& T_world_camera, double from, double to,
                     std::mt19937& random, const Eigen::Vector3d& start = kEdgeStart,
                     const Eigen::Vector3d& end = kEdgeEnd) {
  std::normal_distribution<double> noise(0.0, kPixelSigma);
  LineObservation observation;
  observation.camera = kCamera;
  observation.T_world_camera.pose = T_world_camera;
  observation.T_world_camera.covariance = diagonalPoseCovariance(1e-4, 1e-5);
  const Eigen::Vector2d a = project(T_world_camera, start + from * (end - start));
  const Eigen::Vector2d b = project(T_world_camera, start + to * (end - start));
  observation.segment.start = (a + Eigen::Vector2d(noise(random), noise(random))).cast<float>();
  observation.segment.end = (b + Eigen::Vector2d(noise(random), noise(random))).cast<float>();
  const Eigen::Matrix2f covariance =
      Eigen::Matrix2f::Identity() * static_cast<float>(kPixelSigma * kPixelSigma);
  observation.segment.start_covariance = covariance;
  observation.segment.end_covariance = covariance;
  return observation;
}

// Five views 1 m apart along the street, each seeing most of the edge from
// `start` to `end`.
std::vector<LineObservation> drivePast(std::mt19937& random,
                                       const Eigen::Vector3d& start = kEdgeStart,
                                       const Eigen::Vector3d& end = kEdgeEnd) {
  std::vector<LineObservation> views;
  for (int k = 0; k < 5; ++k) {
    views.push_back(
        view(cameraAt(1.0 + k, 0.2), 0.05 * k, 1.0 - 0.05 * (4 - k), random, start, end));
  }
  return views;
}

// The offset of `point` from the line through `start` and `end`, across it.
Eigen::Vector3d offsetFromLine(const Eigen::Vector3d& point,
                               const Eigen::Vector3d& start = kEdgeStart,
                               const Eigen::Vector3d& end = kEdgeEnd) {
  const Eigen::Vector3d u = (end - start).normalized();
  const Eigen::Vector3d offset = point - start;
  return offset - offset.dot(u) * u;
}

// e^T Sigma^+ e for the rank-two covariance across the line.
double chi2Across(const Eigen::Vector3d& offset, const Eigen::Matrix3d& covariance) {
  return offset.dot(covariance.completeOrthogonalDecomposition().pseudoInverse() * offset);
}

TEST(LineTriangulation, AFacadeEdgeLiesWithinItsCovarianceOfTheTruth) {
  std::mt19937 random(3);
  int within = 0;
  std::vector<double> errors_m;
  constexpr int kTrials = 60;
  for (int trial = 0; trial < kTrials; ++trial) {
    const LineTriangulation triangulated =
        triangulateLine(drivePast(random), LineTriangulationOptions{});
    ASSERT_TRUE(triangulated.line) << triangulated.refusal;
    const TriangulatedLine& line = *triangulated.line;
    EXPECT_EQ(line.dof, 4);
    EXPECT_NEAR(line.direction.norm(), 1.0, 1e-9);
    EXPECT_NEAR(line.direction.dot(line.moment), 0.0, 1e-9) << "a Plücker line";
    const Eigen::Vector3d start_offset = offsetFromLine(line.start_world);
    const Eigen::Vector3d end_offset = offsetFromLine(line.end_world);
    within += chi2Across(start_offset, line.start_covariance) <= kChi2TwoDof &&
              chi2Across(end_offset, line.end_covariance) <= kChi2TwoDof;
    errors_m.push_back(std::max(start_offset.norm(), end_offset.norm()));
  }
  EXPECT_GE(within, kTrials - 3) << "at the 99.73 % gate, allowing for chance";
  std::ranges::nth_element(errors_m, errors_m.begin() + kTrials / 2);
  EXPECT_LT(errors_m[kTrials / 2], 0.05) << "median error within 5 cm";
}

// The views reach 0-0.8, 0.05-0.85, ..., 0.2-1.0 of the edge: at least two
// of them see 0.05-0.95.
TEST(LineTriangulation, RunsOverTheStretchTwoViewsSee) {
  std::mt19937 random(5);
  const LineTriangulation triangulated =
      triangulateLine(drivePast(random), LineTriangulationOptions{});
  ASSERT_TRUE(triangulated.line) << triangulated.refusal;
  const Eigen::Vector3d u = kEdgeEnd - kEdgeStart;
  std::array<double, 2> along = {(triangulated.line->start_world - kEdgeStart).dot(u),
                                 (triangulated.line->end_world - kEdgeStart).dot(u)};
  std::ranges::sort(along);
  EXPECT_NEAR(along[0] / u.squaredNorm(), 0.05, 0.02);
  EXPECT_NEAR(along[1] / u.squaredNorm(), 0.95, 0.02);
}

// The window's top edge runs along the street: every view's plane holds it
// and the cameras' path, so the views alone do not fix it. In its wall, each
// view's plane meets the wall in it.
TEST(LineTriangulation, AnEdgeAlongTheStreetIsFixedOnlyInItsWall) {
  std::mt19937 random(7);
  const LineTriangulation free =
      triangulateLine(drivePast(random, kTopStart, kTopEnd), LineTriangulationOptions{});
  EXPECT_FALSE(free.line);
  EXPECT_NE(free.refusal.find("planes"), std::string::npos) << free.refusal;

  const Plane wall{Eigen::Vector3d::UnitX(), 10.0};
  int within = 0;
  constexpr int kTrials = 30;
  for (int trial = 0; trial < kTrials; ++trial) {
    const LineTriangulation triangulated =
        triangulateLine(drivePast(random, kTopStart, kTopEnd), LineTriangulationOptions{}, wall);
    ASSERT_TRUE(triangulated.line) << triangulated.refusal;
    const TriangulatedLine& line = *triangulated.line;
    EXPECT_EQ(line.dof, 2);
    EXPECT_NEAR(line.start_world.x(), 10.0, 1e-9);
    EXPECT_NEAR(line.end_world.x(), 10.0, 1e-9);
    EXPECT_NEAR(line.direction.x(), 0.0, 1e-9);
    // In the wall the error has one dimension left: chi^2_1(0.9973) = 9.0.
    within +=
        chi2Across(offsetFromLine(line.start_world, kTopStart, kTopEnd), line.start_covariance) <=
            9.0 &&
        chi2Across(offsetFromLine(line.end_world, kTopStart, kTopEnd), line.end_covariance) <= 9.0;
  }
  EXPECT_GE(within, kTrials - 2);
}

TEST(LineTriangulation, RefusesTooFewViewsATooShortBaselineASegmentOfNoLengthAndCoincidentPlanes) {
  std::mt19937 random(9);
  std::vector<LineObservation> two = drivePast(random);
  two.resize(2);
  EXPECT_FALSE(triangulateLine(two, LineTriangulationOptions{}).line);

  std::vector<LineObservation> standing;
  for (int k = 0; k < 5; ++k) {
    standing.push_back(view(cameraAt(3.0, 0.05 * k), 0.0, 1.0, random));
  }
  const LineTriangulation from_one_place = triangulateLine(standing, LineTriangulationOptions{});
  EXPECT_FALSE(from_one_place.line);
  EXPECT_NE(from_one_place.refusal.find("within"), std::string::npos) << from_one_place.refusal;

  std::vector<LineObservation> pointlike = drivePast(random);
  pointlike[1].segment.end = pointlike[1].segment.start;
  const LineTriangulation no_length = triangulateLine(pointlike, LineTriangulationOptions{});
  EXPECT_FALSE(no_length.line);
  EXPECT_NE(no_length.refusal.find("view 1"), std::string::npos) << no_length.refusal;

  // An edge along the street at camera height: every view's plane holds the
  // street's axis through the cameras, so all are one plane.
  const Eigen::Vector3d along_start(5.0, 0.0, 1.6);
  const Eigen::Vector3d along_end(5.0, 20.0, 1.6);
  std::vector<LineObservation> edge_on;
  for (int k = 0; k < 5; ++k) {
    edge_on.push_back(view(cameraAt(-10.0 + k, -0.3), 0.3, 0.7, random, along_start, along_end));
  }
  const LineTriangulation coincident = triangulateLine(edge_on, LineTriangulationOptions{});
  EXPECT_FALSE(coincident.line);
  EXPECT_NE(coincident.refusal.find("planes"), std::string::npos) << coincident.refusal;
}

// One view's segment is another edge, 0.4 m further along the wall: no line
// fits every view.
TEST(LineTriangulation, RefusesALineOneViewSawElsewhere) {
  std::mt19937 random(13);
  std::vector<LineObservation> views = drivePast(random);
  views[2] = view(cameraAt(3.0, 0.2), 0.1, 0.9, random, kEdgeStart + Eigen::Vector3d(0, 0.4, 0),
                  kEdgeEnd + Eigen::Vector3d(0, 0.4, 0));
  const LineTriangulation triangulated = triangulateLine(views, LineTriangulationOptions{});
  EXPECT_FALSE(triangulated.line);
  EXPECT_NE(triangulated.refusal.find("chi^2"), std::string::npos) << triangulated.refusal;
}

}  // namespace
}  // namespace lineloc
