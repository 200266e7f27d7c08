// The robot's front end on a fisheye (an equidistant lens, Kannala & Brandt),
// calibrated as Kalibr writes it (camchain.yaml, pinhole-equi): the simulator
// renders the bundled Delft street through the lens (sim/render/camera_rays.h),
// the robot reads the camchain, undistorts the image's edges onto the
// calibration's pinhole camera and fits its lines there. Lines fitted right
// lie on the model's edges seen from the true pose: the backbone's gate
// (line_matcher.h, no pose uncertainty) takes many more of them for model
// lines than from a pose 1 m to the side, and, where the lens bends most,
// than if the lens were taken for a pinhole; and every one lies within the
// undistorted view.
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <opencv2/imgcodecs.hpp>

#include "backbone/matching/line_matcher.h"
#include "backbone/tracker/model_file.h"
#include "robot/vision/features/feature_extractor.h"
#include "tests/support/delft_drive.h"

namespace fs = std::filesystem;

namespace lineloc {
namespace {

// A 640 x 480 fisheye of 184 degrees across: theta = 320 / 200 px at the
// image's side.
constexpr char kFisheyeCamchain[] = R"(cam0:
  camera_model: pinhole
  distortion_model: equidistant
  distortion_coeffs: [0.015, -0.006, 0.001, -0.0002]
  intrinsics: [200.0, 200.0, 319.5, 239.5]
  resolution: [640, 480]
)";

constexpr double kSideStepM = 1.0;

// Beyond this distance from the principal point a ray is 43 degrees or more
// off the axis, and a pinhole model of the lens puts it f (tan(theta) -
// theta) >= 36 px from where the lens does, far outside any gate.
constexpr double kPeripheryPx = 150.0;

struct Explained {
  int all = 0;
  int periphery = 0;
};

// The segments `T_world_camera` explains (gated to a visible model line), of
// all and of those whose middle lies in the periphery.
Explained explained(const std::vector<ImageSegment>& segments, const TrackedModel& model,
                    const OcclusionScene& scene, const Eigen::Isometry3d& T_world_camera,
                    const PinholeCamera& camera, const VisibilityOptions& visibility) {
  const PoseWithCovariance exact{T_world_camera, Matrix6d::Zero()};
  const std::vector<std::vector<LineMatch>> candidates = gateCandidates(
      segments, visibleSegments(model.lines, scene, exact, camera, visibility), exact, camera, {});
  Explained counts;
  for (size_t i = 0; i < segments.size(); ++i) {
    if (candidates[i].empty()) {
      continue;
    }
    ++counts.all;
    const Eigen::Vector2d middle = 0.5 * (segments[i].start + segments[i].end).cast<double>();
    counts.periphery += (middle - Eigen::Vector2d(camera.cx, camera.cy)).norm() > kPeripheryPx;
  }
  return counts;
}

Explained& operator+=(Explained& sum, const Explained& counts) {
  sum.all += counts.all;
  sum.periphery += counts.periphery;
  return sum;
}

TEST(FisheyeFrontEnd, LinesFromAFisheyeLieOnTheModelsEdges) {
  const fs::path work = fs::temp_directory_path() / fmt::format("fisheye_{}", getpid());
  fs::remove_all(work);
  fs::create_directories(work);
  std::ofstream(work / "camchain.yaml") << kFisheyeCamchain;
  const CameraCalibration fisheye = readCameraCalibration((work / "camchain.yaml").string());
  ASSERT_EQ(fisheye.lens, LensModel::kEquidistant);

  DriveSimulationConfig config;
  config.seed = 4;
  config.duration_s = 8.0;
  config.camera_rate_hz = 1.0;
  config.camera_calibration = (work / "camchain.yaml").string();
  const test::SimulatedFrames drive = test::simulateDelftDrive(config, work / "dataset");
  ASSERT_GE(drive.images.size(), 8u);
  const TrackedModel model =
      readLocalModel(test::delftCityModel().string(), test::delftSiteOrigin(), std::nullopt).model;
  const OcclusionScene scene(model.faces, model.face_building_ids);
  VisibilityOptions visibility;
  visibility.sunlight = drivingSunlight(config);

  CameraCalibration as_pinhole = fisheye;
  as_pinhole.lens = LensModel::kRadialTangential;
  as_pinhole.distortion.clear();
  FeatureExtractor with_lens(fisheye);
  FeatureExtractor without_lens(as_pinhole);
  int segments = 0;
  Explained true_pose, beside, lens_ignored;
  for (size_t frame = 0; frame < drive.images.size(); ++frame) {
    const cv::Mat image = cv::imread(drive.images[frame], cv::IMREAD_GRAYSCALE);
    const std::vector<ImageSegment> lines = with_lens.extract(image).segments;
    for (const ImageSegment& segment : lines) {
      for (const Eigen::Vector2f& end : {segment.start, segment.end}) {
        EXPECT_TRUE(end.x() >= 0.0f && end.x() <= 639.0f && end.y() >= 0.0f && end.y() <= 479.0f)
            << frame << ": " << end.transpose();
      }
    }
    segments += static_cast<int>(lines.size());
    true_pose += explained(lines, model, scene, drive.truth[frame], fisheye.camera, visibility);
    beside += explained(lines, model, scene,
                        drive.truth[frame] * Eigen::Translation3d(kSideStepM, 0.0, 0.0),
                        fisheye.camera, visibility);
    lens_ignored += explained(without_lens.extract(image).segments, model, scene,
                              drive.truth[frame], fisheye.camera, visibility);
  }
  fmt::print(
      "{} segments from {} fisheye frames on model edges (of them beyond 43 degrees off the "
      "axis): {} ({}) from the true pose, {} ({}) from 1 m aside, {} ({}) with the lens taken "
      "for a pinhole\n",
      segments, drive.images.size(), true_pose.all, true_pose.periphery, beside.all,
      beside.periphery, lens_ignored.all, lens_ignored.periphery);
  EXPECT_GE(true_pose.all, 10 * static_cast<int>(drive.images.size()));
  EXPECT_GE(true_pose.all, 2 * beside.all);
  // Where the lens bends most, only its model finds the model's edges.
  EXPECT_GE(true_pose.periphery, 4 * lens_ignored.periphery);
  if (!HasFailure()) {
    fs::remove_all(work);
  }
}

}  // namespace
}  // namespace lineloc
