// Tracking on recorded frames of simulated Delft drives: what the robot sent
// (camera, the image segments with their covariances, the predicted pose and
// covariance) and the true pose, each in a data file; the model is the bundled
// Delft model. An OK answer must hold the truth within three standard
// deviations (e^T Sigma^-1 e below chi^2_6(0.9973)).
//
// Window edges (seed 37, frame 2 of the 50-drive measurement): the robot
// stands at a building corner, the previous frame's fix was 1 cm off, and its
// reported covariance (0.15 m, 0.3 degrees) is conservative, as the jackknife
// makes it. The façades carry window frames a few pixels beside the building
// edges. With gates as wide as that covariance, half the true building edges
// have two model lines inside their gate and are left out as ambiguous, while
// window edges, each near one model line only, are kept: they pulled the pose
// 0.5 m off with a 5 cm standard deviation. This frame must be answered.
//
// Few model lines (seed 11 at one frame per second, frame 11): nine model
// segments are visible and the prediction is the truth, 1 cm and 0.02 degrees
// uncertain. The first round's seven matches leave the pose ill-conditioned;
// gated again with that wide covariance, 22 candidates came in, and the
// alignment settled 1.3 m off along the view reporting 0.2 m (e^T Sigma^-1 e
// 220). Not answering OK is right here: nine segments do not fix the pose.
//
// A prediction short along the view (seed 10 at 30 frames per second, frame
// 120): the prediction is 0.15 m behind the truth along the view with a
// 0.16 m sigma, as the first frame after a search can be. The view's lines fit
// two depths about 0.13 m apart; from the prediction's centre the alignment
// settled in the near one reporting 5 cm (e^T Sigma^-1 e 60), from the truth
// within 2 cm. The same frame with a 25 times smaller predicted covariance
// (3 cm): a prediction as confident as a filter that fused correlated fixes
// as independent; the sigma points must still reach the truth's basin.
//
// A corner the sun lights alike (seed 13 at 30 frames per second, frame 324,
// driving): the prediction has slid 0.33 m back along the view with a 3 cm
// sigma. The building's corners lie between walls the sun lights alike and
// give no image edge; the window columns inset from them fit the model's
// outline from the prediction (15 inliers, 0.33 m back, e^T Sigma^-1 e 78).
// Told the sun, visibility drops those corners and the alignment returns to
// the truth. So that the frame keeps testing that, it must give the precise
// wrong pose when the sun is not known.
//
// An ill-conditioned view (seed 35, frame 450, driving): the robot's own
// prediction, 3 cm from the truth with a 1.8 cm sigma. From it eleven
// segments match and leave the pose ill-conditioned; from one sigma point
// eight of them gave an OK alignment 1.2 m off reporting 0.4 m (e^T Sigma^-1
// e 121). Where the view does not determine the pose from the prediction, an
// answer that depends on where the alignment started is no answer.
//
// Beyond the prediction's reach (seed 23, frame 458, driving): the robot's
// own prediction, 8 cm from the truth with a 2.5 cm sigma. The alignment from
// it settled 0.47 m away reporting 0.16 m (e^T Sigma^-1 e 87 against the
// truth): the image and the prediction disagree, and the answer must say so.
#include <gtest/gtest.h>

#include <fstream>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "backbone/matching/localizer.h"
#include "backbone/tracker/model_file.h"
#include "tests/support/delft_drive.h"
#include "tests/support/pose_error.h"

namespace lineloc {
namespace {

struct RecordedFrame {
  PinholeCamera camera;
  Eigen::Isometry3d truth = Eigen::Isometry3d::Identity();
  PoseWithCovariance predicted;
  std::vector<ImageSegment> segments;
};

Eigen::Isometry3d readPose(std::istream& in) {
  double x, y, z, qx, qy, qz, qw;
  in >> x >> y >> z >> qx >> qy >> qz >> qw;
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() = Eigen::Quaterniond(qw, qx, qy, qz).normalized().toRotationMatrix();
  pose.translation() = Eigen::Vector3d(x, y, z);
  return pose;
}

Eigen::Matrix2f readCovariance(std::istream& in) {
  float xx, xy, yy;
  in >> xx >> xy >> yy;
  return (Eigen::Matrix2f() << xx, xy, xy, yy).finished();
}

// One record per line: camera, truth, predicted, predicted_covariance,
// segment (see the data file).
RecordedFrame readRecordedFrame(const std::string& path) {
  std::ifstream file(path);
  if (!file) {
    throw std::runtime_error(path + ": cannot open");
  }
  RecordedFrame frame;
  std::string line;
  for (int number = 1; std::getline(file, line); ++number) {
    std::istringstream in(line);
    std::string record;
    in >> record;
    if (record == "camera") {
      in >> frame.camera.fx >> frame.camera.fy >> frame.camera.cx >> frame.camera.cy >>
          frame.camera.skew >> frame.camera.width >> frame.camera.height;
    } else if (record == "truth") {
      frame.truth = readPose(in);
    } else if (record == "predicted") {
      frame.predicted.pose = readPose(in);
    } else if (record == "predicted_covariance") {
      for (int i = 0; i < 36; ++i) {
        in >> frame.predicted.covariance(i / 6, i % 6);
      }
    } else if (record == "segment") {
      ImageSegment segment;
      in >> segment.start.x() >> segment.start.y() >> segment.end.x() >> segment.end.y();
      segment.start_covariance = readCovariance(in);
      segment.end_covariance = readCovariance(in);
      frame.segments.push_back(segment);
    }
    if (!in) {
      throw std::runtime_error(path + ":" + std::to_string(number) + ": malformed " + record);
    }
  }
  return frame;
}

struct LocalizedFrame {
  RecordedFrame frame;
  Localization localization;
};

// The backbone as the demo runs it: told the sun the drives are rendered under.
LocalizerOptions sunlit() {
  LocalizerOptions options;
  options.visibility.sunlight = drivingSunlight(DriveSimulationConfig{});
  return options;
}

// The recorded frame `name` (tests/integration/drive/data), localized with
// `options`, its predicted covariance scaled by `covariance_scale`.
LocalizedFrame localizeRecordedFrame(const std::string& name,
                                     const LocalizerOptions& options = sunlit(),
                                     double covariance_scale = 1.0) {
  LocalizedFrame result{
      readRecordedFrame(std::string(LINELOC_SOURCE_DIR) + "/tests/integration/drive/data/" + name),
      {}};
  result.frame.predicted.covariance *= covariance_scale;
  const RecordedFrame& frame = result.frame;
  EXPECT_FALSE(needsAcquisition(frame.predicted, {}));
  const TrackedModel model =
      readLocalModel(test::delftCityModel().string(), test::delftSiteOrigin(), std::nullopt).model;
  const OcclusionScene scene(model.faces, model.face_building_ids);
  result.localization =
      localize(frame.segments, {}, model.lines, scene, frame.predicted, frame.camera, options);
  return result;
}

// e^T Sigma^-1 e of the answer against the truth.
double normalizedError(const LocalizedFrame& localized) {
  return test::normalizedErrorSquared(localized.localization.alignment.T_world_camera,
                                      localized.frame.truth);
}

// Fails when the answer is beyond three sigma of the truth.
void expectWithinThreeSigma(const LocalizedFrame& localized) {
  const Alignment& alignment = localized.localization.alignment;
  const Eigen::Isometry3d& truth = localized.frame.truth;
  const Eigen::Vector3d error_camera =
      truth.linear().transpose() *
      (alignment.T_world_camera.pose.translation() - truth.translation());
  EXPECT_LT(normalizedError(localized), test::kChi2Six9973)
      << "position error in the camera frame (m): " << error_camera.transpose() << ", "
      << alignment.inliers << " inliers";
}

TEST(DelftTrackingFrame, WindowEdgesBesideTheBuildingEdgesDoNotPullThePose) {
  const LocalizedFrame localized = localizeRecordedFrame("delft_window_edges_frame.txt");
  const Alignment& alignment = localized.localization.alignment;
  ASSERT_EQ(alignment.status, AlignmentStatus::kOk) << alignment.message;
  expectWithinThreeSigma(localized);
}

TEST(DelftTrackingFrame, AnUnderdeterminedRoundDoesNotWidenTheGates) {
  const LocalizedFrame localized = localizeRecordedFrame("delft_few_model_lines_frame.txt");
  if (localized.localization.alignment.status == AlignmentStatus::kOk) {
    expectWithinThreeSigma(localized);
  }
}

TEST(DelftTrackingFrame, APredictionShortAlongTheViewGivesNoPreciseWrongPose) {
  const LocalizedFrame localized = localizeRecordedFrame("delft_prediction_short_frame.txt");
  if (localized.localization.alignment.status == AlignmentStatus::kOk) {
    expectWithinThreeSigma(localized);
  }
}

TEST(DelftTrackingFrame, APredictionOverconfidentAboutAWrongDepthGivesNoPreciseWrongPose) {
  const LocalizedFrame localized =
      localizeRecordedFrame("delft_prediction_short_frame.txt", sunlit(), 0.04);
  if (localized.localization.alignment.status == AlignmentStatus::kOk) {
    expectWithinThreeSigma(localized);
  }
}

TEST(DelftTrackingFrame, CornersTheSunLightsAlikeDoNotHoldAPredictionThatSlidBack) {
  const LocalizedFrame localized = localizeRecordedFrame("delft_corner_lit_alike_frame.txt");
  ASSERT_EQ(localized.localization.alignment.status, AlignmentStatus::kOk)
      << localized.localization.alignment.message;
  expectWithinThreeSigma(localized);

  const LocalizedFrame sun_unknown =
      localizeRecordedFrame("delft_corner_lit_alike_frame.txt", LocalizerOptions{});
  ASSERT_EQ(sun_unknown.localization.alignment.status, AlignmentStatus::kOk);
  EXPECT_GT(normalizedError(sun_unknown), test::kChi2Six9973);
}

// The alignment these frames were recorded with (a wide loss, ground lines
// as sure as the rest, no façade-side cut, a position sigma limit of 0.5 m),
// under which they fail as described; tracking's narrower loss answers both right (3 and 1 cm off),
// which the second half of each test checks.
LocalizerOptions asRecorded() {
  LocalizerOptions options = sunlit();
  options.alignment.loss_scale_sigma = 2.0;
  options.alignment.max_position_sigma_m = 0.5;
  options.alignment.ground_line_sigma_m = options.alignment.model_sigma_m;
  options.alignment.facade_side_cut_sigma = std::numeric_limits<double>::infinity();
  return options;
}

void expectRightIfOk(const LocalizedFrame& localized) {
  if (localized.localization.alignment.status == AlignmentStatus::kOk) {
    expectWithinThreeSigma(localized);
  }
}

TEST(DelftTrackingFrame, AnIllConditionedViewIsNotAnsweredFromASigmaPoint) {
  const LocalizedFrame localized =
      localizeRecordedFrame("delft_ill_conditioned_view_frame.txt", asRecorded());
  EXPECT_EQ(localized.localization.alignment.status, AlignmentStatus::kIllConditioned)
      << localized.localization.alignment.message;
  expectRightIfOk(localizeRecordedFrame("delft_ill_conditioned_view_frame.txt"));
}

TEST(DelftTrackingFrame, AnAlignmentBeyondThePredictionsReachIsInconsistent) {
  const LocalizedFrame localized =
      localizeRecordedFrame("delft_beyond_prediction_reach_frame.txt", asRecorded());
  EXPECT_EQ(localized.localization.alignment.status, AlignmentStatus::kInconsistent)
      << localized.localization.alignment.message;
  expectRightIfOk(localizeRecordedFrame("delft_beyond_prediction_reach_frame.txt"));
}

}  // namespace
}  // namespace lineloc
