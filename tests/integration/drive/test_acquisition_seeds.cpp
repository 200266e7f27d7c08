// No precise wrong pose from a poor start (paper §3.2: "a false match gives a
// precise but wrong pose"): each seed simulates the start of a different
// drive through the Delft model (its own route, clutter and sensor noise),
// and the backbone's LineSet handler — real PostGIS map — is given three
// frames half a second apart with a prediction that is off by one draw of
// the start's error, the same for every frame (it wanders over a minute),
// with the robot's own motion between the frames exact (dead reckoning over
// half a second). The first two frames start searches (each finished before
// the next frame); the third is tracked from the pose they found, when the
// second confirmed the first. Every drive starts standing still, so all
// frames see the same view: the second search confirms that the first was
// not a matter of image noise, nothing more.
//
// The third frame's answer, when FIX_OK, must hold the truth within the 6-D
// equivalent of three standard deviations of its reported covariance:
// e^T Sigma^-1 e below chi^2_6(0.9973) = 20.06. Other answers are allowed
// (the robot searches again on its next frames); wrong precise ones are
// counted and must be none. So that a test cannot pass by never answering,
// enough seeds must be fixed from these frames alone.
//
// The starts: a DGPS + compass start (4 m per axis, 0.5 degrees of yaw) on
// the renders' streets; a 1 m / 3 degree start on those streets and on
// streets furnished as real ones are (cables across them, trees over the
// roof lines, lane lines, kerbs: sim/world/street_furniture.h), and on
// streets furnished three times as thickly (a cable every 8 m, a tall tree
// every 17 m, which crowd the sky), where the searches must fix as many
// drives, wrongly none; and on furnished streets
// a start 40 m off with the stated 1 m / 3 degrees, whose region does not
// hold the truth: no answer may be OK. And with a 5 megapixel camera, of the
// default camera's field of view and of 90 degrees: the 1 m / 3 degree
// starts on plain streets must be decided as the default camera's, those on
// furnished streets fixed as often, wrongly none, and the starts 40 m off on
// furnished streets answered OK never.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <map>
#include <opencv2/imgcodecs.hpp>
#include <random>
#include <string>

#include "backbone/map/database_tile_fetcher.h"
#include "backbone/service/line_set_handler.h"
#include "robot/vision/features/feature_extractor.h"
#include "sim/render/sample_camera.h"
#include "tests/support/child_process.h"
#include "tests/support/delft_drive.h"
#include "tests/support/pose_error.h"
#include "tests/support/test_database.h"

namespace fs = std::filesystem;

namespace lineloc {
namespace {

constexpr uint32_t kFrames = 3;

// How a start's prediction is off: each position axis by a draw of
// position_sigma_m (or, with offset_m, horizontally by offset_m in a drawn
// direction), the yaw by a draw of yaw_sigma_rad; and the covariance it
// states.
struct StartError {
  double position_sigma_m = 0.0;
  double yaw_sigma_rad = 0.0;
  double offset_m = 0.0;
};

struct Outcome {
  int fixed = 0;
  int wrong = 0;
  // Each seed's answer to its third frame.
  std::map<int, std::string> answers;
};

// What the drives are rendered with: streets furnished or not (see above),
// and the camera's calibration file (empty: the default 640 x 480 camera).
struct Streets {
  std::string name;
  bool furnished = false;
  std::string camera_calibration;
  // Cables and tall trees of furnished streets, this many times as many.
  double furniture_scale = 1.0;
};

const Streets kPlain{"plain", false, ""};
const Streets kFurnished{"furnished", true, ""};
const Streets kThicklyFurnished{"thickly-furnished", true, "", 3.0};

// The start of seed's drive: kFrames frames 0.5 s apart and their true poses.
test::SimulatedFrames simulateStart(const fs::path& folder, uint64_t seed, const Streets& streets) {
  DriveSimulationConfig config;
  config.seed = seed;
  config.duration_s = 0.5 * kFrames - 0.4;
  config.camera_rate_hz = 2.0;
  config.camera_calibration = streets.camera_calibration;
  if (streets.furnished) {
    config.clutter.tall_trees_per_100m = 2.0 * streets.furniture_scale;
    config.furniture.cables_per_100m = 4.0 * streets.furniture_scale;
    config.furniture.lane_markings = true;
    config.furniture.kerbs = true;
  }
  return test::simulateDelftDrive(config, folder);
}

LineSetData lineSet(const std::vector<ImageSegment>& segments, const PinholeCamera& camera,
                    uint32_t sequence, const PoseWithCovariance& predicted,
                    const std::string& robot_id = "seeded") {
  LineSetData data;
  data.robot_id = robot_id;
  data.sequence_number = sequence;
  data.stamp_ns = 1'000'000'000LL + sequence * 500'000'000LL;
  data.camera = camera;
  data.segments = segments;
  data.predicted_T_world_camera = predicted;
  data.camera_height_m = test::kDelftCameraHeightM;
  return data;
}

class AcquisitionSeeds : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    work_ = fs::temp_directory_path() / ("acquisition_seeds_" + std::to_string(getpid()));
    fs::remove_all(work_);
    fs::create_directories(work_);
    database_ = new test::TestDatabase("acquisition_seeds");
    std::vector<std::string> args = {"--db", database_->conninfo(test::DatabaseRole::kWriter),
                                     "--site", "delft", "--site-origin"};
    const std::vector<std::string> origin = test::delftSiteOriginArgs();
    args.insert(args.end(), origin.begin(), origin.end());
    args.push_back(test::delftCityModel().string());
    test::ChildProcess load(std::string(LINELOC_BIN_DIR) + "/lineloc-load", args,
                            (work_ / "load.log").string());
    writeFiveMegapixelCamera();
    loaded_ = load.wait(120'000) == std::optional<int>(0);
  }
  static void TearDownTestSuite() {
    delete database_;
    database_ = nullptr;
    fs::remove_all(work_);
  }
  void SetUp() override { ASSERT_TRUE(loaded_) << "lineloc-load failed: " << work_ / "load.log"; }

  // Seeds first..last started with `error`, on `streets`.
  static Outcome runStarts(int first, int last, const StartError& error, const Streets& streets) {
    MapTileCache map(
        [] {
          return makeDatabaseTileFetcher(database_->conninfo(test::DatabaseRole::kReader), "delft");
        },
        100.0, 1024);
    // The backbone knows the sun, as the demo's does.
    PipelineOptions pipeline;
    pipeline.localizer.visibility.sunlight = drivingSunlight(DriveSimulationConfig{});
    Outcome outcome;
    for (int seed = first; seed <= last; ++seed) {
      const test::SimulatedFrames start =
          simulateStart(work_ / fmt::format("{}-{}", seed, streets.name), seed, streets);
      EXPECT_GE(start.images.size(), kFrames);
      if (start.images.size() < kFrames) {
        continue;
      }
      std::mt19937 random(static_cast<uint32_t>(1000 + seed));
      std::normal_distribution<double> n(0.0, 1.0);
      Eigen::Vector3d position_error(error.position_sigma_m * n(random),
                                     error.position_sigma_m * n(random),
                                     error.position_sigma_m * n(random));
      const Eigen::Matrix3d yaw_error =
          Eigen::AngleAxisd(error.yaw_sigma_rad * n(random), Eigen::Vector3d::UnitZ())
              .toRotationMatrix();
      if (error.offset_m > 0.0) {
        const double bearing = std::uniform_real_distribution<double>(0.0, 2.0 * M_PI)(random);
        position_error = error.offset_m * Eigen::Vector3d(std::cos(bearing), std::sin(bearing), 0);
      }
      // A fresh handler per seed: no robot state carries over. Its map, which
      // a backbone prepares once for the robots around it, is prepared first
      // (another robot's frame, answered without a pose while it is).
      LineSetHandler handler(map, MessageLimits{}, pipeline);
      const auto predictedAt = [&](uint32_t frame) {
        PoseWithCovariance predicted;
        predicted.pose.linear() = yaw_error * start.truth[frame].linear();
        predicted.pose.translation() = start.truth[frame].translation() + position_error;
        predicted.covariance = diagonalPoseCovariance(error.position_sigma_m, error.yaw_sigma_rad);
        return predicted;
      };
      handler.handle(
          LineSetMessage(lineSet({}, start.calibration.camera, 0, predictedAt(0), "map-warm-up"))
              .message());
      handler.waitForSearches();
      FeatureExtractor extractor(start.calibration);
      std::optional<PoseFixData> answer;
      for (uint32_t frame = 0; frame < kFrames; ++frame) {
        const std::vector<ImageSegment> segments =
            extractor.extract(cv::imread(start.images[frame], cv::IMREAD_GRAYSCALE)).segments;
        answer = handler.handle(
            LineSetMessage(lineSet(segments, start.calibration.camera, frame, predictedAt(frame)))
                .message());
        EXPECT_TRUE(answer.has_value());
        if (!answer) {
          break;
        }
        handler.waitForSearches();
      }
      outcome.answers[seed] = answer ? toString(answer->status) : "dropped";
      if (!answer || answer->status != lineloc_msg_FIX_OK) {
        fmt::print("seed {} ({}): {}\n", seed, streets.name, outcome.answers[seed]);
        continue;
      }
      ++outcome.fixed;
      const double nees =
          test::normalizedErrorSquared(answer->T_world_camera, start.truth[kFrames - 1]);
      const double error_m =
          (answer->T_world_camera.pose.translation() - start.truth[kFrames - 1].translation())
              .norm();
      fmt::print("seed {} ({}): ok, error {:.3f} m, e^T S^-1 e {:.1f}\n", seed, streets.name,
                 error_m, nees);
      if (nees > test::kChi2Six9973) {
        ++outcome.wrong;
        ADD_FAILURE() << "seed " << seed << ": a precise wrong pose, " << error_m
                      << " m off, e^T Sigma^-1 e " << nees;
      }
    }
    fmt::print("{}: {} of seeds {}-{} fixed from {} frames, {} precise wrong poses\n", streets.name,
               outcome.fixed, first, last, kFrames, outcome.wrong);
    return outcome;
  }

  // A 5 megapixel camera (2464 x 2056) with the default camera's lens and
  // field of view across, its principal point scaled alike.
  static void writeFiveMegapixelCamera() {
    CameraCalibration five_megapixel = opencvSampleCamera();
    PinholeCamera& camera = five_megapixel.camera;
    const double s = 2464.0 / camera.width;
    camera = {s * camera.fx, s * camera.fy, s * camera.cx, s * camera.cy, 0.0, 2464, 2056};
    camera.cy = 0.5 * camera.height;
    writeCameraCalibration(fiveMegapixelCalibration(), five_megapixel);
    // And a wide one: 90 degrees across, an undistorted lens.
    CameraCalibration wide;
    wide.camera = {1232.0, 1232.0, 1232.0, 1028.0, 0.0, 2464, 2056};
    writeCameraCalibration(wideFiveMegapixelCalibration(), wide);
  }
  static std::string fiveMegapixelCalibration() { return (work_ / "five_megapixel.yaml").string(); }
  static std::string wideFiveMegapixelCalibration() {
    return (work_ / "wide_five_megapixel.yaml").string();
  }
  static Streets plainAtFiveMegapixels() {
    return {"plain-5mp", false, fiveMegapixelCalibration()};
  }
  static Streets furnishedAtFiveMegapixels() {
    return {"furnished-5mp", true, fiveMegapixelCalibration()};
  }
  static Streets furnishedWideAtFiveMegapixels() {
    return {"furnished-wide-5mp", true, wideFiveMegapixelCalibration()};
  }

  static fs::path work_;
  static test::TestDatabase* database_;
  static bool loaded_;
};

fs::path AcquisitionSeeds::work_;
test::TestDatabase* AcquisitionSeeds::database_ = nullptr;
bool AcquisitionSeeds::loaded_ = false;

TEST_F(AcquisitionSeeds, NoPrecisePoseIsWrongOverFiftyDgpsStarts) {
  const Outcome outcome = runStarts(1, 50, {4.0, 0.5 * M_PI / 180.0}, kPlain);
  EXPECT_EQ(outcome.wrong, 0);
  EXPECT_GE(outcome.fixed, 16);
}

TEST_F(AcquisitionSeeds, FurnishedStreetsAreFixedAsOftenFromAMetreAndThreeDegrees) {
  const StartError metre{1.0, 3.0 * M_PI / 180.0};
  const Outcome plain = runStarts(51, 70, metre, kPlain);
  const Outcome furnished = runStarts(51, 70, metre, kFurnished);
  const Outcome thickly = runStarts(51, 70, metre, kThicklyFurnished);
  EXPECT_EQ(plain.wrong + furnished.wrong + thickly.wrong, 0);
  EXPECT_GE(plain.fixed, 6);
  EXPECT_GE(furnished.fixed, plain.fixed - 2);
  EXPECT_GE(thickly.fixed, plain.fixed - 1);
}

TEST_F(AcquisitionSeeds, AStartWhoseRegionMissesTheTruthIsNeverAnsweredOk) {
  const StartError forty_metres_off{1.0, 3.0 * M_PI / 180.0, 40.0};
  EXPECT_EQ(runStarts(71, 90, forty_metres_off, kFurnished).fixed, 0);
  EXPECT_EQ(runStarts(71, 80, forty_metres_off, furnishedAtFiveMegapixels()).fixed, 0);
  EXPECT_EQ(runStarts(71, 80, forty_metres_off, furnishedWideAtFiveMegapixels()).fixed, 0);
}

// The same starts seen by a 5 megapixel camera: the searches, which measure
// the image in angles, decide alike. The two front ends do not see the same
// segments (the sharper image resolves edges the coarser one blurs), so a
// seed may still be decided otherwise; measured in pixels of each camera, the
// two decide most seeds differently. On furnished streets the 5 megapixel
// camera fixes as many, wrongly none.
TEST_F(AcquisitionSeeds, AFiveMegapixelCameraIsDecidedAsTheDefaultOne) {
  const StartError metre{1.0, 3.0 * M_PI / 180.0};
  const Outcome default_camera = runStarts(91, 100, metre, kPlain);
  const Outcome sharp = runStarts(91, 100, metre, plainAtFiveMegapixels());
  const Outcome furnished = runStarts(91, 100, metre, furnishedAtFiveMegapixels());
  EXPECT_EQ(default_camera.wrong + sharp.wrong + furnished.wrong, 0);
  int alike = 0;
  for (const auto& [seed, answer] : default_camera.answers) {
    alike += sharp.answers.contains(seed) && sharp.answers.at(seed) == answer ? 1 : 0;
  }
  EXPECT_GE(alike, 8);
  EXPECT_GE(furnished.fixed, sharp.fixed - 2);
  const Outcome wide = runStarts(91, 100, metre, furnishedWideAtFiveMegapixels());
  EXPECT_EQ(wide.wrong, 0);
  EXPECT_GE(wide.fixed, default_camera.fixed - 2);
}

}  // namespace
}  // namespace lineloc
