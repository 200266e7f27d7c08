#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>
#include <optional>
#include <utility>

#include "sim/render/city_renderer.h"
#include "sim/render/sample_camera.h"
#include "tests/unit/sim/render/quarter_camera.h"

namespace lineloc {
namespace {

// Camera 1.5 m above the ground looking along world +x, yawed by `yaw_rad`.
Eigen::Isometry3d forwardLookingCamera(double yaw_rad = 0.0) {
  Eigen::Matrix3d R_body_camera;
  R_body_camera << 0, 0, 1, -1, 0, 0, 0, -1, 0;
  Eigen::Isometry3d T_world_camera = Eigen::Isometry3d::Identity();
  T_world_camera.linear() = Eigen::AngleAxisd(yaw_rad, Eigen::Vector3d::UnitZ()) * R_body_camera;
  T_world_camera.translation() = Eigen::Vector3d(0.0, 0.0, 1.5);
  return T_world_camera;
}

struct Box {
  Eigen::Isometry3d T_world_box;
  Eigen::Vector3d half_size;

  // Slab test: distance along the unit ray to the box, if it is hit.
  std::optional<double> intersect(const Eigen::Vector3d& origin,
                                  const Eigen::Vector3d& direction) const {
    const Eigen::Vector3d o = T_world_box.inverse() * origin;
    const Eigen::Vector3d d = T_world_box.linear().transpose() * direction;
    double t_enter = 0.0;
    double t_exit = std::numeric_limits<double>::infinity();
    for (int axis = 0; axis < 3; ++axis) {
      const double t1 = (-half_size[axis] - o[axis]) / d[axis];
      const double t2 = (half_size[axis] - o[axis]) / d[axis];
      t_enter = std::max(t_enter, std::min(t1, t2));
      t_exit = std::min(t_exit, std::max(t1, t2));
    }
    if (t_enter > t_exit) {
      return std::nullopt;
    }
    return t_enter;
  }
};

Box rotatedBox() {
  Eigen::Isometry3d T_world_box = Eigen::Isometry3d::Identity();
  T_world_box.linear() = Eigen::AngleAxisd(0.5, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  T_world_box.translation() = Eigen::Vector3d(9.0, 0.8, 2.0);
  return {T_world_box, Eigen::Vector3d(1.5, 2.0, 1.8)};
}

SceneMesh meshOf(const Box& box) {
  SceneMesh mesh;
  mesh.addBox(box.T_world_box, box.half_size, SurfaceTag{SurfaceKind::kWall, 1, 0.2f, 3.8f});
  return mesh;
}

RenderOptions noiselessOptions() {
  RenderOptions options;
  options.noise_sigma = 0.0f;
  return options;
}

// The world ray of pixel (u, v) computed by OpenCV's own iterative undistortion.
Eigen::Vector3d openCvRay(const CameraCalibration& calibration,
                          const Eigen::Isometry3d& T_world_camera, double u, double v) {
  const cv::Matx33d K(calibration.camera.fx, 0.0, calibration.camera.cx, 0.0, calibration.camera.fy,
                      calibration.camera.cy, 0.0, 0.0, 1.0);
  std::vector<cv::Point2d> undistorted;
  cv::undistortPoints(
      std::vector<cv::Point2d>{{u, v}}, undistorted, K, calibration.distortion, cv::noArray(),
      cv::noArray(), cv::TermCriteria(cv::TermCriteria::COUNT | cv::TermCriteria::EPS, 200, 1e-15));
  return T_world_camera.linear() *
         Eigen::Vector3d(undistorted[0].x, undistorted[0].y, 1.0).normalized();
}

// The rendered silhouette of a box agrees with the box seen through OpenCV's
// camera model at every pixel centre farther than 0.3 px from its outline: a
// pixel that disagrees must agree somewhere on the 0.3 px circle around it.
void expectBoxWhereOpenCvSeesIt(const CameraCalibration& calibration) {
  const Box box = rotatedBox();
  const CityRenderer renderer(meshOf(box), calibration, noiselessOptions());
  const Eigen::Isometry3d T_world_camera = forwardLookingCamera(0.1);
  const PixelHits hits = renderer.castPrimaryRays(T_world_camera);
  const Eigen::Vector3d origin = T_world_camera.translation();
  constexpr double kEdgeTolerance_px = 0.3;
  int box_pixels = 0;
  int disagreements = 0;
  for (int v = 0; v < hits.height; v += 2) {
    for (int u = 0; u < hits.width; u += 2) {
      const size_t index = static_cast<size_t>(v) * hits.width + u;
      const bool rendered_box =
          hits.triangle[index] != kNoTriangle && hits.triangle[index] != kGroundTriangle;
      const std::optional<double> t =
          box.intersect(origin, openCvRay(calibration, T_world_camera, u, v));
      box_pixels += rendered_box;
      if (rendered_box && t) {
        // float ray directions and hit distance on a ~10 m ray: ~1e-5 m.
        EXPECT_NEAR(hits.distance_m[index], *t, 1e-3) << "pixel " << u << "," << v;
      }
      if (rendered_box == t.has_value()) {
        continue;
      }
      ++disagreements;
      bool agrees_nearby = false;
      for (int k = 0; k < 16 && !agrees_nearby; ++k) {
        const double angle = k * std::numbers::pi / 8.0;
        const Eigen::Vector3d d =
            openCvRay(calibration, T_world_camera, u + kEdgeTolerance_px * std::cos(angle),
                      v + kEdgeTolerance_px * std::sin(angle));
        agrees_nearby = box.intersect(origin, d).has_value() == rendered_box;
      }
      EXPECT_TRUE(agrees_nearby) << "pixel " << u << "," << v << " more than " << kEdgeTolerance_px
                                 << " px inside the wrong side of the edge";
    }
  }
  EXPECT_GT(box_pixels, 5000);
  EXPECT_LT(disagreements, 20);
}

TEST(CityRenderer, BoxEdgesLieWhereOpenCvProjectsThemWithDistortion) {
  expectBoxWhereOpenCvSeesIt(opencvSampleCamera());
}

TEST(CityRenderer, BoxEdgesLieWhereOpenCvProjectsThemForAPinhole) {
  CameraCalibration calibration = opencvSampleCamera();
  calibration.distortion.clear();
  expectBoxWhereOpenCvSeesIt(calibration);
}

TEST(CityRenderer, SameSeedSameBytesOtherSeedOtherNoise) {
  const CityRenderer renderer(meshOf(rotatedBox()), quarterCamera(), RenderOptions{});
  const Eigen::Isometry3d pose = forwardLookingCamera();
  const cv::Mat a = renderer.renderImage(pose, pose, 42);
  const cv::Mat b = renderer.renderImage(pose, pose, 42);
  const cv::Mat c = renderer.renderImage(pose, pose, 43);
  EXPECT_EQ(cv::norm(a, b, cv::NORM_INF), 0.0);
  EXPECT_GT(cv::norm(a, c, cv::NORM_INF), 0.0);
}

TEST(CityRenderer, SensorNoiseHasTheConfiguredSigma) {
  RenderOptions options;
  options.noise_sigma = 3.0f;
  const CityRenderer renderer(meshOf(rotatedBox()), quarterCamera(), options);
  const Eigen::Isometry3d pose = forwardLookingCamera();
  cv::Mat clean;
  renderer.renderRadiance(pose).convertTo(clean, CV_32F, 255.0);
  cv::Mat noisy;
  renderer.renderImage(pose, pose, 5).convertTo(noisy, CV_32F);
  cv::Scalar mean;
  cv::Scalar sigma;
  cv::meanStdDev(noisy - clean, mean, sigma);
  // Rounding to integers adds variance 1/12: sqrt(9 + 1/12) = 3.014. With
  // 19,200 samples the sample sigma has a relative standard error of
  // 1/sqrt(2 n) = 0.5%; 3% allows six of those plus pixels clipped at 0 or 255.
  EXPECT_NEAR(sigma[0], std::sqrt(9.0 + 1.0 / 12.0), 0.09);
  EXPECT_NEAR(mean[0], 0.0, 0.1);  // standard error 3 / sqrt(19,200) = 0.02
}

// The ideal camera's image of light_fraction f of the scene's light is
// round(255 f radiance): within half a grey level of it.
TEST(CityRenderer, IdealImageScalesWithTheLightFraction) {
  const CityRenderer renderer(meshOf(rotatedBox()), quarterCamera(), noiselessOptions());
  const Eigen::Isometry3d pose = forwardLookingCamera();
  cv::Mat scaled_radiance;
  renderer.renderRadiance(pose).convertTo(scaled_radiance, CV_32F, 255.0 * 0.25);
  cv::Mat image;
  renderer.renderImage(pose, pose, 1, 0.25f).convertTo(image, CV_32F);
  EXPECT_LE(cv::norm(image, scaled_radiance, cv::NORM_INF), 0.5 + 1e-3);
  // The scene is there, a quarter as bright.
  EXPECT_GT(cv::norm(image, cv::NORM_INF), 20.0);
  EXPECT_EQ(cv::countNonZero(renderer.renderImage(pose, pose, 1, 0.0f)), 0);
}

TEST(CityRenderer, ShadowedGroundIsLitOnlyByAmbientLight) {
  RenderOptions options = noiselessOptions();
  options.shading.sun_direction = Eigen::Vector3f(-0.5f, 0.0f, 0.8f).normalized();
  const Box box = rotatedBox();
  const CityRenderer renderer(meshOf(box), opencvSampleCamera(), options);
  const Eigen::Isometry3d pose = forwardLookingCamera(0.1);
  const PixelHits hits = renderer.castPrimaryRays(pose);
  const cv::Mat radiance = renderer.renderRadiance(pose);
  double sum[2] = {0.0, 0.0};
  int count[2] = {0, 0};
  const Eigen::Vector3d sun = options.shading.sun_direction.cast<double>();
  for (int v = 0; v < hits.height; ++v) {
    for (int u = 0; u < hits.width; ++u) {
      const size_t index = static_cast<size_t>(v) * hits.width + u;
      if (hits.triangle[index] != kGroundTriangle) {
        continue;
      }
      const Eigen::Vector3d d = (pose.linear() * renderer.rays().direction(u, v).cast<double>());
      const Eigen::Vector3d ground = pose.translation() + hits.distance_m[index] * d;
      const bool shadowed = box.intersect(ground, sun).has_value();
      sum[shadowed] += radiance.at<float>(v, u);
      ++count[shadowed];
    }
  }
  ASSERT_GT(count[0], 1000);
  ASSERT_GT(count[1], 1000);
  // Lambert: shadow / lit = ambient / (ambient + (1 - ambient) s_z). The
  // asphalt grain (uniform +-4% of albedo per 25 cm cell) averages over
  // hundreds of cells to well under 1%; 3% tolerance.
  const double ambient = options.shading.ambient;
  const double expected = ambient / (ambient + (1.0 - ambient) * sun.z());
  EXPECT_NEAR((sum[1] / count[1]) / (sum[0] / count[0]), expected, 0.03 * expected);
}

TEST(CityRenderer, MotionBlurSmearsOnlyWhenTheCameraMoves) {
  RenderOptions options = noiselessOptions();
  options.motion_blur_samples = 4;
  const CityRenderer blurred(meshOf(rotatedBox()), quarterCamera(), options);
  const CityRenderer sharp(meshOf(rotatedBox()), quarterCamera(), noiselessOptions());
  const Eigen::Isometry3d open = forwardLookingCamera(0.1);
  const Eigen::Isometry3d close = forwardLookingCamera(0.14);
  const cv::Mat still = blurred.renderImage(open, open, 0);
  // The mean of 4 equal renders differs from one render by float rounding only.
  EXPECT_LE(cv::norm(still, sharp.renderImage(open, open, 0), cv::NORM_INF), 1.0);
  const cv::Mat moving = blurred.renderImage(open, close, 0);
  cv::Mat gradient_still;
  cv::Mat gradient_moving;
  cv::Sobel(still, gradient_still, CV_32F, 1, 0);
  cv::Sobel(moving, gradient_moving, CV_32F, 1, 0);
  // A 0.04 rad pan is ~5 px at this resolution: vertical edges spread and weaken.
  EXPECT_LT(cv::norm(gradient_moving, cv::NORM_INF), 0.8 * cv::norm(gradient_still, cv::NORM_INF));
}

TEST(CityRenderer, AnExposureTakesAsManyRendersAsItsMotionNeeds) {
  RenderOptions options = noiselessOptions();
  options.motion_blur_samples = 8;
  const CameraCalibration calibration = quarterCamera();
  const CityRenderer renderer(meshOf(rotatedBox()), calibration, options);
  const Eigen::Isometry3d open = forwardLookingCamera(0.1);
  EXPECT_EQ(renderer.blurSamples(open, open), 1);
  // d = theta fx: 1.2 px of pan take ceil(1.2 / 0.5) = 3 renders.
  EXPECT_EQ(renderer.blurSamples(open, forwardLookingCamera(0.1 + 1.2 / calibration.camera.fx)), 3);
  // |dt| fx / 2 m: 1.7 px of travel take 4.
  Eigen::Isometry3d moved = open;
  moved.translation().x() += 2.0 * 1.7 / calibration.camera.fx;
  EXPECT_EQ(renderer.blurSamples(open, moved), 4);
  EXPECT_EQ(renderer.blurSamples(open, forwardLookingCamera(0.14)), 8) << "at most the option's";
}

TEST(CityRenderer, AnExposureTakesItsHalfwayRenderWhenGivenIt) {
  RenderOptions options = noiselessOptions();
  options.motion_blur_samples = 3;
  const CityRenderer renderer(meshOf(rotatedBox()), quarterCamera(), options);
  const Eigen::Isometry3d open = forwardLookingCamera(0.1);
  const Eigen::Isometry3d close = forwardLookingCamera(0.14);
  const cv::Mat centre = renderer.renderRadiance(forwardLookingCamera(0.12));
  EXPECT_EQ(cv::norm(renderer.renderExposureRadiance(open, close, centre),
                     renderer.renderExposureRadiance(open, close), cv::NORM_INF),
            0.0);
  // The given render is used, not a new one.
  EXPECT_GT(cv::norm(renderer.renderExposureRadiance(open, close, cv::Mat(0.0f * centre)),
                     renderer.renderExposureRadiance(open, close), cv::NORM_INF),
            0.0);
}

// What a pixel on a wall's vertical edge sees beside the wall: each is an edge
// by another clause of the edge rule.
enum class BesideTheEdge {
  kSky,
  // The box is turned 45 degrees: its corner is a crease between two faces of
  // one object, lit differently.
  kAnotherFaceOfTheSameObject,
  // A wall of the same object facing the same way, its front face 2.5 m
  // behind the near one's (a depth step of 25 %), in the near one's shadow.
  kTheSameObjectFarther,
};

// A wall straight ahead whose left vertical edge falls at `edge_u` in the
// pinhole sample camera: the edge pixel's radiance tells the share c of it
// that the wall covers, (I - beside) / (wall - beside) from its neighbours,
// and a pixel integrating its area gives c = edge_u's distance to the pixel's
// right border, to 1 / 32 with 16 lattice rays (16 distinct columns).
double coverageError(int edge_pixel_samples, double edge_u, BesideTheEdge beside) {
  CameraCalibration calibration = opencvSampleCamera();
  calibration.distortion.clear();
  const PinholeCamera& camera = calibration.camera;
  RenderOptions options = noiselessOptions();
  options.shadows = beside == BesideTheEdge::kTheSameObjectFarther;
  options.edge_pixel_samples = edge_pixel_samples;
  // From the camera's side: the face on the edge's right (normal -x or, turned,
  // (-1, -1) / sqrt(2)) is lit, the one on its left is not.
  options.shading.sun_direction = Eigen::Vector3f(-0.5f, -0.7f, 0.5f).normalized();
  // The camera looks along world +x with image u along world -y: the edge at
  // depth 10 m sits at world y = (cx - edge_u) 10 / fx.
  constexpr double kDepth_m = 10.0;
  const double edge_y = (camera.cx - edge_u) * kDepth_m / camera.fx;
  constexpr double kHalfWidth_m = 2.0;
  const SurfaceTag tag{SurfaceKind::kPole, 1, 0.0f, 4.0f};
  Eigen::Isometry3d T_world_wall = Eigen::Isometry3d::Identity();
  SceneMesh mesh;
  if (beside == BesideTheEdge::kAnotherFaceOfTheSameObject) {
    // Corner (-a, a) of a box turned 45 degrees about z points at the camera:
    // R (-a, a) = (-a sqrt(2), 0).
    T_world_wall.linear() =
        Eigen::AngleAxisd(std::numbers::pi / 4.0, Eigen::Vector3d::UnitZ()).matrix();
    T_world_wall.translation() =
        Eigen::Vector3d(kDepth_m + kHalfWidth_m * std::numbers::sqrt2, edge_y, 2.0);
    mesh.addBox(T_world_wall, Eigen::Vector3d(kHalfWidth_m, kHalfWidth_m, 2.0), tag);
  } else {
    T_world_wall.translation() = Eigen::Vector3d(kDepth_m + 0.5, edge_y - kHalfWidth_m, 2.0);
    mesh.addBox(T_world_wall, Eigen::Vector3d(0.5, kHalfWidth_m, 2.0), tag);
  }
  if (beside == BesideTheEdge::kTheSameObjectFarther) {
    Eigen::Isometry3d T_world_far_wall = T_world_wall;
    T_world_far_wall.translation() += Eigen::Vector3d(2.5, 2.0 * kHalfWidth_m, 0.0);
    mesh.addBox(T_world_far_wall, Eigen::Vector3d(0.5, 3.0 * kHalfWidth_m, 2.0), tag);
  }
  const CityRenderer renderer(mesh, calibration, options);
  const cv::Mat radiance = renderer.renderRadiance(forwardLookingCamera());
  const int v = static_cast<int>(std::lround(camera.cy)) - 20;
  const int u = static_cast<int>(std::lround(edge_u));
  const float beside_radiance = radiance.at<float>(v, u - 2);
  const float wall = radiance.at<float>(v, u + 2);
  EXPECT_GT(std::abs(wall - beside_radiance), 0.1f) << "no contrast to measure coverage with";
  const double covered = (radiance.at<float>(v, u) - beside_radiance) / (wall - beside_radiance);
  return std::abs(covered - (u + 0.5 - edge_u));
}

TEST(CityRenderer, AnEdgePixelIsTheMeanOverItsArea) {
  for (const auto& [beside, name] :
       {std::pair{BesideTheEdge::kSky, "the sky"},
        std::pair{BesideTheEdge::kAnotherFaceOfTheSameObject, "a crease"},
        std::pair{BesideTheEdge::kTheSameObjectFarther, "a depth step"}}) {
    SCOPED_TRACE(name);
    for (const double fraction : {0.1, 0.3, 0.45, 0.6, 0.85}) {
      const double edge_u = 200.5 + fraction;
      EXPECT_LE(coverageError(16, edge_u, beside), 1.0 / 32.0 + 0.005) << "edge at u = " << edge_u;
    }
    // One ray per pixel puts the edge on a pixel border.
    EXPECT_GT(coverageError(1, 200.8, beside), 0.25);
  }
}

TEST(CityRenderer, TheGroundEndsAtTheHorizonRange) {
  // A camera pitched up until one pixel's ray dips a hair below the horizon:
  // that ray meets the ground plane farther than any scene is and is the
  // sky's, so no shading point lies beyond the range a ray caster takes. The
  // scene's one triangle stands behind the camera.
  SceneMesh behind;
  behind.addTriangle({-50, 0, 0}, {-50, 1, 0}, {-50, 0, 1}, SurfaceTag{});
  const CityRenderer renderer(behind, quarterCamera(), noiselessOptions());
  const int u = 60;
  const int v = 100;
  const Eigen::Isometry3d level = forwardLookingCamera();
  const Eigen::Vector3d ray =
      (level.linear() * renderer.rays().direction(u, v).cast<double>()).normalized();
  // Turning about the horizontal axis across the ray, z x ray, by -delta
  // raises the ray's elevation by delta.
  const Eigen::Vector3d across = Eigen::Vector3d::UnitZ().cross(ray).normalized();
  for (const double dip_rad : {1e-3, 1e-6, 1e-9}) {
    Eigen::Isometry3d T_world_camera = level;
    const double raise_rad = -dip_rad - std::asin(ray.z());
    T_world_camera.linear() = Eigen::AngleAxisd(-raise_rad, across) * level.linear();
    const PixelHits hits = renderer.castPrimaryRays(T_world_camera);
    const size_t index = static_cast<size_t>(v) * hits.width + u;
    const double distance_m = 1.5 / std::sin(dip_rad);
    if (distance_m <= 1e7) {
      EXPECT_EQ(hits.triangle[index], kGroundTriangle) << "dip " << dip_rad;
      EXPECT_NEAR(hits.distance_m[index], distance_m, 1e-3 * distance_m) << "dip " << dip_rad;
    } else {
      EXPECT_EQ(hits.triangle[index], kNoTriangle) << "dip " << dip_rad;
    }
    EXPECT_TRUE(cv::checkRange(renderer.renderRadiance(T_world_camera)));
  }
}

TEST(CityRenderer, RejectsInvalidOptions) {
  RenderOptions options;
  options.motion_blur_samples = 0;
  EXPECT_THROW(CityRenderer(SceneMesh{}, quarterCamera(), options), std::invalid_argument);
  options = RenderOptions{};
  options.edge_pixel_samples = 0;
  EXPECT_THROW(CityRenderer(SceneMesh{}, quarterCamera(), options), std::invalid_argument);
  options.edge_pixel_samples = kRayPacketSize + 1;
  EXPECT_THROW(CityRenderer(SceneMesh{}, quarterCamera(), options), std::invalid_argument);
  options = RenderOptions{};
  options.exposure = 0.0f;
  EXPECT_THROW(CityRenderer(SceneMesh{}, quarterCamera(), options), std::invalid_argument);
  options = RenderOptions{};
  options.shading.sun_direction = Eigen::Vector3f(0.0f, 0.0f, 2.0f);
  EXPECT_THROW(CityRenderer(SceneMesh{}, quarterCamera(), options), std::invalid_argument);
}

}  // namespace
}  // namespace lineloc
