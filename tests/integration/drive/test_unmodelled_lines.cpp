// What the robot's image lines on the README's main drive (the bundled Delft
// model, seed 1, 120 s, seen once a second) say about the city model the
// backbone matches them with. Each frame is rendered by the simulator and its
// segments are extracted with the robot's default settings.
//
// How many come from things the model does not hold (paper §3.2: parked cars,
// trees, façade detail). A segment is explained by the model when the
// backbone's gate (line_matcher.h) takes it for a model line visible from the
// true pose under the drive's sun (the demo tells the backbone the sun), with
// no pose uncertainty: within chi^2_2(0.999) of the line given the segment's
// own endpoint covariance and the 1 px model floor, overlapping it by 30 %.
// Every other segment comes from something not in the model. So that a
// mismatch of frames and poses cannot pass for clutter, the true poses must
// explain at least twice as many segments as poses 1 m to the camera's side,
// where only chance alignments with the model remain. The issue asks that the
// accuracy and availability bounds hold with 30 % of the image lines from
// things not in the model. The demo's drive and the drive test's
// (tests/integration/drive/test_delft_drive.cpp) are this drive or its first
// 30 s; this test fails if the simulated streets ever hold fewer than that, so
// the bounds those runs report are measured at 30 % or more.
//
// Whether the polarity the backbone predicts for a model line (visible_lines.h:
// the sky brighter than a façade against it) agrees with the one the front end
// measures on the segment it extracts there. Each image segment is paired with
// its best candidate from the true pose, polarity not used; where both have a
// polarity, the gate with polarity must still take that pair nearly always:
// else it would throw away true matches. A convention flipped on either
// side (left of start -> end, image y down) agrees on almost none.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <opencv2/imgcodecs.hpp>

#include "backbone/matching/line_matcher.h"
#include "backbone/tracker/model_file.h"
#include "robot/vision/features/feature_extractor.h"
#include "tests/support/delft_drive.h"

namespace fs = std::filesystem;

namespace lineloc {
namespace {

constexpr double kMinUnmodelledFraction = 0.30;
constexpr double kSideStepM = 1.0;
constexpr double kMinPolarityAgreement = 0.95;
constexpr int kMinPolarityPairs = 100;

// The demo's drive seen once a second: each frame's true pose and the
// segments the robot's front end extracts from it, and the model with its
// scene; simulated once per test process.
struct DemoDrive {
  DemoDrive() {
    const fs::path work = fs::temp_directory_path() / ("demo_drive_" + std::to_string(getpid()));
    fs::remove_all(work);
    DriveSimulationConfig config;
    config.seed = 1;
    config.duration_s = 120.0;
    config.camera_rate_hz = 1.0;
    const test::SimulatedFrames drive = test::simulateDelftDrive(config, work);
    camera = drive.calibration.camera;
    truth = drive.truth;
    FeatureExtractor extractor(drive.calibration);
    for (const std::string& image : drive.images) {
      segments.push_back(extractor.extract(cv::imread(image, cv::IMREAD_GRAYSCALE)).segments);
    }
    fs::remove_all(work);
    visibility.sunlight = drivingSunlight(config);
  }

  PinholeCamera camera;
  std::vector<Eigen::Isometry3d> truth;
  std::vector<std::vector<ImageSegment>> segments;
  TrackedModel model =
      readLocalModel(test::delftCityModel().string(), test::delftSiteOrigin(), std::nullopt).model;
  OcclusionScene scene{model.faces, model.face_building_ids};
  VisibilityOptions visibility;
};

const DemoDrive& demoDrive() {
  static const DemoDrive drive;
  return drive;
}

struct LineCounts {
  int segments = 0;
  int unmodelled = 0;
  double length_px = 0.0;
  double unmodelled_length_px = 0.0;
};

double lengthPx(const ImageSegment& segment) {
  return (segment.end - segment.start).cast<double>().norm();
}

// The segments of one frame that no model line visible from T_world_camera
// (under `visibility`) explains.
LineCounts countUnmodelled(const std::vector<ImageSegment>& segments, const TrackedModel& model,
                           const OcclusionScene& scene, const Eigen::Isometry3d& T_world_camera,
                           const PinholeCamera& camera, const VisibilityOptions& visibility) {
  const PoseWithCovariance exact{T_world_camera, Matrix6d::Zero()};
  const std::vector<std::vector<LineMatch>> candidates = gateCandidates(
      segments, visibleSegments(model.lines, scene, exact, camera, visibility), exact, camera, {});
  LineCounts counts;
  for (size_t i = 0; i < segments.size(); ++i) {
    const double length_px = lengthPx(segments[i]);
    ++counts.segments;
    counts.length_px += length_px;
    if (candidates[i].empty()) {
      ++counts.unmodelled;
      counts.unmodelled_length_px += length_px;
    }
  }
  return counts;
}

TEST(UnmodelledLines, AtLeastThirtyPercentOfTheDemoDrivesImageLinesAreNotInTheModel) {
  const DemoDrive& drive = demoDrive();
  ASSERT_GE(drive.segments.size(), 100u);
  LineCounts total;
  int explained_beside = 0;
  for (size_t frame = 0; frame < drive.segments.size(); ++frame) {
    const std::vector<ImageSegment>& segments = drive.segments[frame];
    const LineCounts counts = countUnmodelled(segments, drive.model, drive.scene,
                                              drive.truth[frame], drive.camera, drive.visibility);
    fmt::print("frame {:3d}: {:3d} segments, {:3d} not in the model\n", frame, counts.segments,
               counts.unmodelled);
    const Eigen::Isometry3d beside =
        drive.truth[frame] * Eigen::Translation3d(kSideStepM, 0.0, 0.0);
    const LineCounts counts_beside =
        countUnmodelled(segments, drive.model, drive.scene, beside, drive.camera, drive.visibility);
    explained_beside += counts_beside.segments - counts_beside.unmodelled;
    total.segments += counts.segments;
    total.unmodelled += counts.unmodelled;
    total.length_px += counts.length_px;
    total.unmodelled_length_px += counts.unmodelled_length_px;
  }
  ASSERT_GT(total.segments, 0);
  const double fraction = static_cast<double>(total.unmodelled) / total.segments;
  fmt::print(
      "{} of {} image segments ({:.1f} %, {:.1f} % of their length) come from things "
      "not in the model\n",
      total.unmodelled, total.segments, 100.0 * fraction,
      100.0 * total.unmodelled_length_px / total.length_px);
  EXPECT_GE(fraction, kMinUnmodelledFraction);
  const int explained = total.segments - total.unmodelled;
  fmt::print("the model explains {} segments from the true poses, {} from {} m beside them\n",
             explained, explained_beside, kSideStepM);
  EXPECT_GE(explained, 2 * explained_beside);
}

struct PolarityPairs {
  int agree = 0;
  int disagree = 0;
};

// Each image segment's best candidate from the true pose without polarity,
// where both have one: agreeing when the gate with polarity still takes it.
PolarityPairs comparePolarities(const std::vector<ImageSegment>& segments,
                                const std::vector<VisibleSegment>& visible,
                                const PoseWithCovariance& truth, const PinholeCamera& camera) {
  MatchingOptions without_polarity;
  without_polarity.use_polarity = false;
  const std::vector<std::vector<LineMatch>> candidates =
      gateCandidates(segments, visible, truth, camera, without_polarity);
  const std::vector<std::vector<LineMatch>> with_polarity =
      gateCandidates(segments, visible, truth, camera, {});
  PolarityPairs pairs;
  for (size_t i = 0; i < segments.size(); ++i) {
    if (candidates[i].empty()) {
      continue;
    }
    const int best = candidates[i].front().model_index;
    if (visible[best].polarity == 0 || segments[i].polarity == 0) {
      continue;
    }
    const bool kept =
        std::any_of(with_polarity[i].begin(), with_polarity[i].end(),
                    [best](const LineMatch& match) { return match.model_index == best; });
    ++(kept ? pairs.agree : pairs.disagree);
  }
  return pairs;
}

TEST(LinePolarity, TheModelsPredictionAgreesWithTheImageWhereBothTell) {
  const DemoDrive& drive = demoDrive();
  PolarityPairs total;
  for (size_t frame = 0; frame < drive.segments.size(); ++frame) {
    const PoseWithCovariance truth{drive.truth[frame], Matrix6d::Zero()};
    const PolarityPairs pairs = comparePolarities(
        drive.segments[frame],
        visibleSegments(drive.model.lines, drive.scene, truth, drive.camera, drive.visibility),
        truth, drive.camera);
    total.agree += pairs.agree;
    total.disagree += pairs.disagree;
  }
  const int pairs = total.agree + total.disagree;
  fmt::print("{} of {} model lines with a predicted polarity agree with their image segment\n",
             total.agree, pairs);
  ASSERT_GE(pairs, kMinPolarityPairs);
  EXPECT_GE(total.agree, kMinPolarityAgreement * pairs);
}

}  // namespace
}  // namespace lineloc
