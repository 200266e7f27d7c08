// lineloc-track on the model of an object in its own frame, without a CRS:
// four solids about 30 cm across (a box with a smaller box on it, a low box
// and a ramp), rendered by lineloc-sim's realistic camera (bare walls, no
// street clutter) from a small robot circling them 0.4-1 m away, its camera
// 0.35 m up and tilted down. Started 1 cm and 2 degrees off the first frame's
// pose, with those sigmas, the tracker must follow the camera to millimetres
// on every frame, from the z-up CityJSON and from the same object written as a
// y-up OBJ, whose poses it then answers in the OBJ's own axes.
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <sstream>

#include "apps/offline_tracking.h"
#include "common/trajectory/fix_log.h"
#include "common/trajectory/tum_trajectory.h"
#include "sim/dataset/drive_simulation.h"
#include "tests/support/pose_error.h"
#include "tests/support/pose_option.h"

namespace lineloc {
namespace {

namespace fs = std::filesystem;

// A solid: its vertices (m, z up) and its faces, each wound counter-clockwise
// seen from outside.
struct Solid {
  std::vector<Eigen::Vector3d> vertices;
  std::vector<std::vector<int>> faces;
};

Solid box(const Eigen::Vector3d& low, const Eigen::Vector3d& high) {
  Solid solid;
  for (int k = 0; k < 8; ++k) {
    const bool x = k == 1 || k == 2 || k == 5 || k == 6;
    const bool y = k == 2 || k == 3 || k == 6 || k == 7;
    solid.vertices.emplace_back(x ? high.x() : low.x(), y ? high.y() : low.y(),
                                k >= 4 ? high.z() : low.z());
  }
  solid.faces = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4},
                 {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}};
  return solid;
}

// Rising along x from the ground at x0 to `height` at x1.
Solid ramp(double x0, double x1, double y0, double y1, double height) {
  Solid solid;
  solid.vertices = {{x0, y0, 0}, {x1, y0, 0},      {x1, y1, 0},
                    {x0, y1, 0}, {x1, y0, height}, {x1, y1, height}};
  solid.faces = {{0, 3, 2, 1}, {0, 1, 4}, {1, 2, 5, 4}, {2, 3, 5}, {0, 4, 5, 3}};
  return solid;
}

std::vector<Solid> boxesAndRamp() {
  return {box({0.0, 0.0, 0.0}, {0.16, 0.10, 0.08}), box({0.02, 0.02, 0.08}, {0.10, 0.08, 0.14}),
          box({0.20, -0.05, 0.0}, {0.30, 0.05, 0.06}), ramp(0.0, 0.14, 0.14, 0.24, 0.07)};
}

// CityJSON in millimetres, no referenceSystem.
void writeCityJson(const std::vector<Solid>& solids, const fs::path& path) {
  std::string objects;
  std::string vertices;
  int base = 0;
  for (size_t s = 0; s < solids.size(); ++s) {
    std::string surfaces;
    for (const std::vector<int>& face : solids[s].faces) {
      std::string ring;
      for (const int index : face) {
        ring += fmt::format("{}{}", ring.empty() ? "" : ",", base + index);
      }
      surfaces += fmt::format("{}[[{}]]", surfaces.empty() ? "" : ",", ring);
    }
    objects += fmt::format(
        R"({}"part{}":{{"type":"Building","geometry":[{{"type":"MultiSurface","lod":"2","boundaries":[{}]}}]}})",
        objects.empty() ? "" : ",", s, surfaces);
    for (const Eigen::Vector3d& p : solids[s].vertices) {
      vertices += fmt::format("{}[{},{},{}]", vertices.empty() ? "" : ",", std::lround(p.x() * 1e3),
                              std::lround(p.y() * 1e3), std::lround(p.z() * 1e3));
    }
    base += static_cast<int>(solids[s].vertices.size());
  }
  std::ofstream(path) << fmt::format(
      R"({{"type":"CityJSON","version":"2.0","transform":{{"scale":[0.001,0.001,0.001],"translate":[0,0,0]}},"CityObjects":{{{}}},"vertices":[{}]}})",
      objects, vertices);
}

// The OBJ's y-up axes from the z-up frame: (x, y, z) -> (x, z, -y).
Eigen::Isometry3d yUpFromZUp() {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = Eigen::AngleAxisd(-M_PI / 2.0, Eigen::Vector3d::UnitX()).toRotationMatrix();
  return T;
}

void writeYUpObj(const std::vector<Solid>& solids, const fs::path& path) {
  std::ofstream obj(path);
  int base = 1;
  for (size_t s = 0; s < solids.size(); ++s) {
    obj << fmt::format("o part{}\n", s);
    for (const Eigen::Vector3d& p : solids[s].vertices) {
      const Eigen::Vector3d y_up = yUpFromZUp() * p;
      obj << fmt::format("v {} {} {}\n", y_up.x(), y_up.y(), y_up.z());
    }
    for (const std::vector<int>& face : solids[s].faces) {
      obj << "f";
      for (const int index : face) {
        obj << " " << base + index;
      }
      obj << "\n";
    }
    base += static_cast<int>(solids[s].vertices.size());
  }
}

// An ellipse of route around the object, 0.55-0.85 m from its middle; the
// drive covers about half of it.
void writeOrbit(const fs::path& path) {
  std::ofstream route(path);
  for (int k = 0; k <= 180; ++k) {
    const double angle = 2.0 * M_PI * k / 180.0;
    route << fmt::format("{} {}\n", 0.15 + 0.85 * std::cos(angle), 0.10 + 0.55 * std::sin(angle));
  }
}

class OfflineObjectTracking : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    folder_ = fs::temp_directory_path() / ("object_tracking_" + std::to_string(getpid()));
    fs::remove_all(folder_);
    fs::create_directories(folder_);
    writeCityJson(boxesAndRamp(), folder_ / "object.city.json");
    writeYUpObj(boxesAndRamp(), folder_ / "object_y_up.obj");
    writeOrbit(folder_ / "orbit.txt");
    DriveSimulationConfig drive;
    drive.city_model = (folder_ / "object.city.json").string();
    // Only the simulated GNSS needs a place on Earth.
    drive.crs = "EPSG:28992";
    drive.site_origin = {0.0, 0.0, 0.0};
    drive.output = (folder_ / "dataset").string();
    drive.waypoints = (folder_ / "orbit.txt").string();
    drive.seed = 1;
    drive.duration_s = 8.0;
    drive.camera_rate_hz = 20.0;
    drive.camera_height_m = 0.35;
    drive.camera_yaw_deg = 90.0;
    drive.camera_pitch_deg = -25.0;
    drive.facade_detail = false;
    drive.drive.initial_still_s = 0.0;
    drive.drive.initial_speed_m_s = 0.25;
    drive.drive.min_speed_m_s = 0.2;
    drive.drive.max_speed_m_s = 0.3;
    drive.drive.stop_probability = 0.0;
    drive.drive.control_spacing_m = 0.1;
    drive.clutter.cars_per_100m = 0.0;
    drive.clutter.trees_per_100m = 0.0;
    drive.clutter.poles_per_100m = 0.0;
    drive.clutter.pedestrians_per_100m = 0.0;
    simulateDrive(drive);
    for (const StampedPose& pose :
         readTumFile((folder_ / "dataset" / "groundtruth_cam0.tum").string())) {
      truth_[pose.stamp_ns] = pose.pose;
    }
  }
  static void TearDownTestSuite() { fs::remove_all(folder_); }

  // Tracking the object's model from 1 cm and 2 degrees off the first
  // frame's true pose T_model_camera.
  static OfflineTrackingConfig configOff(const std::string& model, const std::string& up_axis,
                                         const Eigen::Isometry3d& T_model_zup) {
    OfflineTrackingConfig config;
    config.drive.city_model = (folder_ / model).string();
    config.model_up_axis = up_axis;
    config.drive.images = (folder_ / "dataset" / "cam0").string();
    config.drive.camera_calibration = (folder_ / "dataset" / "cam0" / "calibration.yaml").string();
    Eigen::Isometry3d start = T_model_zup * truth_.begin()->second;
    start.translation() += 0.01 * Eigen::Vector3d(1.0, -2.0, 2.0) / 3.0;
    start.linear() = Eigen::AngleAxisd(2.0 * M_PI / 180.0, Eigen::Vector3d(2.0, 1.0, -2.0) / 3.0) *
                     start.linear();
    config.predicted_pose = test::poseOptionValues(start);
    config.predicted_position_sigma_m = 0.01;
    config.predicted_rotation_sigma_deg = 2.0;
    config.out = (folder_ / (model + ".tum")).string();
    config.fix_log_out = (folder_ / (model + ".fixes")).string();
    return config;
  }

  // Every frame aligned, each within 2 mm and 0.5 degree of the truth (in the
  // model's axes: T_model_zup times the z-up truth), and inside its own
  // covariance as the robot's fixes must be (chi^2_6 at 0.9973) on all but
  // a rare frame.
  static void expectTrackedToMillimetres(const OfflineTrackingConfig& config,
                                         const Eigen::Isometry3d& T_model_zup) {
    std::ostringstream out;
    const OfflineTrackingSummary summary = runOfflineTracking(config, out);
    ASSERT_EQ(summary.frames, static_cast<int>(truth_.size()));
    EXPECT_EQ(summary.aligned, summary.frames) << out.str();
    const std::vector<LoggedFix> fixes = readFixLog(config.fix_log_out);
    ASSERT_EQ(fixes.size(), truth_.size());
    int beyond_covariance = 0;
    for (const LoggedFix& fix : fixes) {
      const Eigen::Isometry3d truth = T_model_zup * truth_.at(fix.stamp_ns);
      const Eigen::Isometry3d& pose = fix.T_world_camera.pose;
      EXPECT_LT((pose.translation() - truth.translation()).norm(), 0.002) << fix.stamp_ns;
      EXPECT_LT(Eigen::AngleAxisd(pose.linear().transpose() * truth.linear()).angle(),
                0.5 * M_PI / 180.0)
          << fix.stamp_ns;
      beyond_covariance +=
          normalizedErrorSquared(fix.T_world_camera, truth) > test::kChi2Six9973 ? 1 : 0;
    }
    EXPECT_LE(beyond_covariance, summary.frames / 100) << out.str();
    EXPECT_NE(out.str().find("frame = model frame minus site origin (0.000, 0.000, 0.000)"),
              std::string::npos)
        << out.str();
  }

  static fs::path folder_;
  static std::map<int64_t, Eigen::Isometry3d> truth_;
};

fs::path OfflineObjectTracking::folder_;
std::map<int64_t, Eigen::Isometry3d> OfflineObjectTracking::truth_;

TEST_F(OfflineObjectTracking, TracksAZUpModelInItsOwnFrameToMillimetres) {
  expectTrackedToMillimetres(configOff("object.city.json", "z", Eigen::Isometry3d::Identity()),
                             Eigen::Isometry3d::Identity());
}

TEST_F(OfflineObjectTracking, TracksAYUpModelAndAnswersInItsAxes) {
  OfflineTrackingConfig config = configOff("object_y_up.obj", "y", yUpFromZUp());
  config.overlay_dir = (folder_ / "overlays").string();
  expectTrackedToMillimetres(config, yUpFromZUp());
  // The overlays draw the image's corners (yellow rings) beside its
  // segments and the model.
  const cv::Mat overlay = cv::imread((folder_ / "overlays" / "frame_000000.png").string());
  ASSERT_FALSE(overlay.empty());
  cv::Mat corner_colour;
  cv::inRange(overlay, cv::Scalar(0, 220, 220), cv::Scalar(20, 240, 240), corner_colour);
  EXPECT_GT(cv::countNonZero(corner_colour), 0);
}

TEST_F(OfflineObjectTracking, NamesAnUpAxisThatIsNone) {
  OfflineTrackingConfig config = configOff("object.city.json", "x", Eigen::Isometry3d::Identity());
  std::ostringstream out;
  try {
    runOfflineTracking(config, out);
    FAIL() << "up axis x accepted";
  } catch (const std::invalid_argument& error) {
    EXPECT_NE(std::string(error.what()).find("model_up_axis"), std::string::npos) << error.what();
  }
}

}  // namespace
}  // namespace lineloc
