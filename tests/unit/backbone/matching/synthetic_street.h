// A synthetic street for the matching tests: two rows of box buildings of
// different heights, the camera 1.5 m up looking along it, the image segments
// it sees (the visible model pieces with pixel noise) plus clutter that is in
// no model (window frames), and the pose error measures the tests assert on.
#pragma once

#include <random>
#include <vector>

#include "backbone/matching/line_matcher.h"
#include "backbone/visibility/visible_corners.h"
#include "backbone/visibility/visible_lines.h"
#include "tests/support/pose_error.h"

namespace lineloc::testing {

using test::kChi2Six999;
using test::normalizedErrorSquared;

inline const PinholeCamera kCamera{500, 500, 320, 240, 0, 640, 480};
inline constexpr double kPixelSigma = 0.5;
// Grey-level step across every rendered segment (ImageSegment::contrast): a
// building edge in daylight, which searches take (AcquisitionOptions).
inline constexpr float kEdgeContrast = 40.0f;

// Each box is a building of its own.
struct Street {
  std::vector<FaceRing> faces;
  std::vector<int64_t> face_building_ids;
  std::vector<ModelSegment> edges;
  int64_t building_count = 0;
};

inline void addBox(Street& street, double x0, double y0, double x1, double y1, double h) {
  const Eigen::Vector3d c[8] = {{x0, y0, 0}, {x1, y0, 0}, {x1, y1, 0}, {x0, y1, 0},
                                {x0, y0, h}, {x1, y0, h}, {x1, y1, h}, {x0, y1, h}};
  const std::vector<FaceRing> faces = {{c[0], c[3], c[2], c[1]}, {c[4], c[5], c[6], c[7]},
                                       {c[0], c[1], c[5], c[4]}, {c[1], c[2], c[6], c[5]},
                                       {c[2], c[3], c[7], c[6]}, {c[3], c[0], c[4], c[7]}};
  street.faces.insert(street.faces.end(), faces.begin(), faces.end());
  street.face_building_ids.insert(street.face_building_ids.end(), faces.size(),
                                  ++street.building_count);
  const int pairs[12][2] = {{0, 1}, {1, 2}, {2, 3}, {3, 0}, {4, 5}, {5, 6},
                            {6, 7}, {7, 4}, {0, 4}, {1, 5}, {2, 6}, {3, 7}};
  for (const auto& pair : pairs) {
    street.edges.push_back({static_cast<int64_t>(street.edges.size()), 0, c[pair[0]], c[pair[1]]});
  }
}

// Two rows of buildings of different heights along a street running north.
inline Street makeStreet() {
  Street street;
  const double heights[] = {12, 18, 9, 15, 21, 11};
  for (int i = 0; i < 6; ++i) {
    addBox(street, -20, 10 + 25 * i, -8, 30 + 25 * i, heights[i]);
    addBox(street, 8, 5 + 25 * i, 22, 27 + 25 * i, heights[5 - i]);
  }
  return street;
}

inline PoseWithCovariance truePose() {
  Eigen::Matrix3d R_world_camera;  // looking north, level, camera 1.5 m up
  R_world_camera << 1, 0, 0, 0, 0, 1, 0, -1, 0;
  PoseWithCovariance pose;
  pose.pose.linear() =
      Eigen::AngleAxisd(0.1, Eigen::Vector3d::UnitZ()).toRotationMatrix() * R_world_camera;
  pose.pose.translation() = Eigen::Vector3d(1.0, 0.0, 1.5);
  return pose;
}

inline ImageSegment observe(const Eigen::Vector2d& a, const Eigen::Vector2d& b,
                            std::mt19937& random) {
  std::normal_distribution<double> noise(0.0, kPixelSigma);
  ImageSegment segment;
  segment.start = (a + Eigen::Vector2d(noise(random), noise(random))).cast<float>();
  segment.end = (b + Eigen::Vector2d(noise(random), noise(random))).cast<float>();
  segment.start_covariance = Eigen::Matrix2f::Identity() * kPixelSigma * kPixelSigma;
  segment.end_covariance = segment.start_covariance;
  segment.contrast = kEdgeContrast;
  return segment;
}

struct Scene {
  std::vector<VisibleSegment> visible;
  std::vector<ImageSegment> image;
};

// What the camera sees at the true pose: every visible model piece, plus
// `clutter` segments that are in no model (window frames: short, vertical or
// horizontal like the façade lines, anywhere in the image).
inline Scene render(const Street& street, const OcclusionScene& occlusion, int clutter,
                    std::mt19937& random) {
  Scene scene;
  const PoseWithCovariance truth = truePose();
  scene.visible = visibleSegments(street.edges, occlusion, truth, kCamera, {});
  for (const VisibleSegment& segment : scene.visible) {
    const ProjectedSegment p =
        projectSegment(segment.start_world, segment.end_world, truth, kCamera);
    scene.image.push_back(observe(p.start_px, p.end_px, random));
  }
  std::uniform_real_distribution<double> u(40, 600), v(40, 440);
  for (int i = 0; i < clutter; ++i) {
    const Eigen::Vector2d a(u(random), v(random));
    const bool vertical = i % 2 == 0;
    const Eigen::Vector2d b = a + (vertical ? Eigen::Vector2d(0, 30) : Eigen::Vector2d(30, 0));
    scene.image.push_back(observe(a, b, random));
  }
  return scene;
}

inline constexpr double kCornerSigmaPx = 0.5;

// An image corner at `pixel`, as uncertain as the noise the street's corners
// are seen with.
inline ImageCorner cornerAt(const Eigen::Vector2d& pixel) {
  ImageCorner corner;
  corner.position = pixel.cast<float>();
  corner.covariance = Eigen::Matrix2f::Identity() * kCornerSigmaPx * kCornerSigmaPx;
  corner.strength = 100.0f;
  return corner;
}

// The image corners of the model `corners` seen from the truth: the i-th at
// the i-th's projection, with noise.
inline std::vector<ImageCorner> observeCorners(const std::vector<VisibleCorner>& corners,
                                               std::mt19937& random) {
  std::normal_distribution<double> noise(0.0, kCornerSigmaPx);
  std::vector<ImageCorner> image;
  for (const VisibleCorner& corner : corners) {
    const Eigen::Vector2d pixel = projectPoint(corner.p_world, truePose(), kCamera).pixel;
    image.push_back(cornerAt(pixel + Eigen::Vector2d(noise(random), noise(random))));
  }
  return image;
}

inline PoseWithCovariance perturbedPrior(const PoseWithCovariance& truth, std::mt19937& random,
                                         double position_sigma, double rotation_sigma) {
  std::normal_distribution<double> n(0.0, 1.0);
  PoseWithCovariance prior = truth;
  prior.pose.translation() +=
      position_sigma * Eigen::Vector3d(n(random), n(random), 0.3 * n(random));
  prior.pose.linear() =
      Eigen::AngleAxisd(rotation_sigma * n(random), Eigen::Vector3d::UnitZ()).toRotationMatrix() *
      prior.pose.linear();
  prior.covariance = diagonalPoseCovariance(2 * position_sigma, 2 * rotation_sigma);
  return prior;
}

}  // namespace lineloc::testing
