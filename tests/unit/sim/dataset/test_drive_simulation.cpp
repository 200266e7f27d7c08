#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <opencv2/imgcodecs.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "common/geodesy/site_projection.h"
#include "common/nmea/nmea_sentence.h"
#include "common/time/utc_time.h"
#include "common/trajectory/tum_trajectory.h"
#include "sim/dataset/drive_simulation.h"
#include "sim/render/camera_rays.h"
#include "sim/render/camera_sensor.h"
#include "sim/render/sample_camera.h"
#include "tests/unit/sim/dataset/read_file.h"

namespace lineloc {
namespace {

namespace fs = std::filesystem;

DriveSimulationConfig shortDelftDrive(const std::string& name) {
  const fs::path city = fs::path(LINELOC_SOURCE_DIR) / "data" / "citymodels" / "delft.json";
  DriveSimulationConfig config;
  config.city_model = city.string();
  config.output = (fs::temp_directory_path() / ("lineloc_test_drive_" + name)).string();
  fs::remove_all(config.output);
  config.duration_s = 8.0;
  config.drive.initial_still_s = 1.0;
  config.camera_rate_hz = 2.0;
  config.camera_time_offset_s = 0.01;
  return config;
}

// The site frame a dataset's world.yaml describes.
SiteProjection worldProjection(const YAML::Node& world) {
  return SiteProjection(
      world["crs"].as<std::string>(),
      Eigen::Vector3d(world["site_origin"][0].as<double>(), world["site_origin"][1].as<double>(),
                      world["site_origin"][2].as<double>()));
}

// One row of cam0's exposure file: stamp, exposure time (s) and gain (dB), as written.
std::array<std::string, 3> exposureRow(const std::string& row) {
  std::istringstream fields(row);
  std::array<std::string, 3> values;
  std::getline(fields, values[0], ',');
  std::getline(fields, values[1], ',');
  std::getline(fields, values[2]);
  return values;
}

TEST(DriveSimulation, WritesADatasetOfTheDriveThroughDelft) {
  const DriveSimulationConfig config = shortDelftDrive("delft");
  const DriveSimulationSummary summary = simulateDrive(config);
  EXPECT_EQ(summary.images, 17);            // 8 s at 2 Hz, both ends
  EXPECT_EQ(summary.imu_samples, 1601);     // 200 Hz
  EXPECT_EQ(summary.compass_readings, 81);  // 10 Hz
  EXPECT_GE(summary.gps_fixes, 8);
  EXPECT_GT(summary.clutter.cars + summary.clutter.trees + summary.clutter.poles, 0);
  const fs::path root(config.output);
  const std::vector<StampedPose> truth = readTumFile((root / "groundtruth_cam0.tum").string());
  ASSERT_EQ(truth.size(), 17u);
  // The camera rides at its configured height above the street level.
  const std::string world = readAll(root / "world.yaml");
  const double ground_z =
      std::stod(world.substr(world.find("ground_z_m: ") + std::string("ground_z_m: ").size()));
  EXPECT_NEAR(truth[5].pose.translation().z() - ground_z, config.camera_height_m, 1e-6);
  // Image stamps are the camera clock's: truth + 10 ms.
  const std::string images = readAll(root / "cam0" / "data.csv");
  EXPECT_NE(images.find(std::to_string(truth[3].stamp_ns + 10'000'000) + ".png"),
            std::string::npos);
  // A street scene: sky, façades and ground give a wide spread of grey levels.
  const cv::Mat image = cv::imread(
      (root / "cam0" / "data" / (std::to_string(truth[8].stamp_ns + 10'000'000) + ".png")).string(),
      cv::IMREAD_UNCHANGED);
  ASSERT_FALSE(image.empty());
  cv::Scalar mean;
  cv::Scalar sigma;
  cv::meanStdDev(image, mean, sigma);
  EXPECT_GT(sigma[0], 25.0);
  EXPECT_NE(readAll(root / "gps0" / "nmea.txt").find("$GPRMC"), std::string::npos);
}

TEST(DriveSimulation, NmeaSentencesHaveValidChecksumsAndParseBackNearTheTruth) {
  DriveSimulationConfig config = shortDelftDrive("nmea");
  config.duration_s = 20.0;
  config.gps.outage_probability = 0.0;
  config.camera_rate_hz = 1.0;  // ground truth at every fix
  simulateDrive(config);
  const fs::path root(config.output);
  const SiteProjection projection = worldProjection(YAML::LoadFile((root / "world.yaml").string()));
  const std::vector<StampedPose> truth = readTumFile((root / "groundtruth_cam0.tum").string());
  std::istringstream lines(readAll(root / "gps0" / "nmea.txt"));
  std::string line;
  int fixes = 0;
  int sentence = 0;
  while (std::getline(lines, line)) {
    const NmeaParseResult parsed = parseNmeaSentence(line);
    ASSERT_EQ(parsed.status, NmeaStatus::kOk) << line << ": " << parsed.error;
    const auto* gga = std::get_if<GgaSentence>(&parsed.sentence);
    // GGA and RMC alternate, one pair per second from the start.
    const StampedPose& at_fix = truth[sentence++ / 2];
    if (gga == nullptr) {
      continue;
    }
    ++fixes;
    const Eigen::Vector3d p_site =
        projection.toSite({gga->latitude_deg, gga->longitude_deg, gga->altitude_msl_m});
    // DGPS errors are 5-10 m (4 m sigma per axis, correlated); RD New's
    // Helmert transformation adds ~1 m: 30 m is over 5 sigma.
    EXPECT_LT((p_site - at_fix.pose.translation()).head<2>().norm(), 30.0) << line;
  }
  EXPECT_EQ(fixes, 21);
}

TEST(DriveSimulation, RendersUnderTheSunOverTheSiteAtItsStart) {
  DriveSimulationConfig config = shortDelftDrive("clock_sun");
  config.duration_s = 1.0;
  config.camera_rate_hz = 1.0;
  config.drive.start_stamp_ns = parseUtcTime_ns("2026-06-21T12:00:00Z");
  config.sun_from_clock = true;
  simulateDrive(config);
  const fs::path root(config.output);
  const YAML::Node world = YAML::LoadFile((root / "world.yaml").string());
  EXPECT_EQ(world["start_utc"].as<std::string>(), "2026-06-21T12:00:00Z");
  EXPECT_EQ(readTumFile((root / "groundtruth_cam0.tum").string()).front().stamp_ns,
            config.drive.start_stamp_ns);
  const std::optional<Sunlight> sun =
      SiteSun(worldProjection(world), config.ambient).at(config.drive.start_stamp_ns);
  ASSERT_TRUE(sun.has_value());
  // world.yaml gives the sun's angles to 0.001 deg: its direction to 2e-5.
  const Eigen::Vector3d written =
      Sunlight::fromAzimuthElevation(world["sun_azimuth_deg"].as<double>(),
                                     world["sun_elevation_deg"].as<double>(), config.ambient)
          .direction_world;
  EXPECT_LT((written - sun->direction_world).norm(), 2e-5);
  // Not the configured angles, which the clock replaces: a midsummer noon sun
  // stands about 61 deg high in Delft.
  EXPECT_GT(std::abs(world["sun_elevation_deg"].as<double>() - config.sun_elevation_deg), 20.0);
}

TEST(DriveSimulation, ClocksSunBelowTheHorizonIsRefused) {
  DriveSimulationConfig config = shortDelftDrive("night");
  config.drive.start_stamp_ns = parseUtcTime_ns("2026-04-14T22:00:00Z");
  config.sun_from_clock = true;
  try {
    simulateDrive(config);
    FAIL();
  } catch (const std::runtime_error& error) {
    EXPECT_NE(std::string(error.what()).find("below the horizon at 2026-04-14T22:00:00Z"),
              std::string::npos)
        << error.what();
  }
  EXPECT_THROW(drivingSunlight(config), std::invalid_argument);
}

TEST(DriveSimulation, SameSeedSameBytes) {
  DriveSimulationConfig a = shortDelftDrive("bytes_a");
  DriveSimulationConfig b = shortDelftDrive("bytes_b");
  a.duration_s = b.duration_s = 3.0;
  simulateDrive(a);
  simulateDrive(b);
  int files = 0;
  for (const auto& entry : fs::recursive_directory_iterator(a.output)) {
    if (entry.is_regular_file()) {
      ++files;
      EXPECT_EQ(readAll(entry.path()),
                readAll(fs::path(b.output) / fs::relative(entry.path(), a.output)))
          << entry.path();
    }
  }
  EXPECT_GT(files, 10);
}

// FNV-1a (64 bit) of the pixel bytes of every image of a dataset, in stamp order.
uint64_t imageFingerprint(const fs::path& root) {
  std::vector<fs::path> images;
  for (const auto& entry : fs::directory_iterator(root / "cam0" / "data")) {
    images.push_back(entry.path());
  }
  std::sort(images.begin(), images.end());
  uint64_t hash = 14'695'981'039'346'656'037ull;
  for (const fs::path& path : images) {
    const cv::Mat image = cv::imread(path.string(), cv::IMREAD_UNCHANGED);
    for (int v = 0; v < image.rows; ++v) {
      for (int u = 0; u < image.cols; ++u) {
        hash = (hash ^ image.at<uint8_t>(v, u)) * 1'099'511'628'211ull;
      }
    }
  }
  return hash;
}

// The ideal camera's images of this drive are the renderer's 255 x radiance
// plus Gaussian noise of noise_sigma, bytes that the fingerprint pins.
TEST(DriveSimulation, IdealCameraKeepsTheRenderersImages) {
  DriveSimulationConfig config = shortDelftDrive("ideal");
  config.duration_s = 1.0;
  config.ideal_camera = true;
  simulateDrive(config);
  EXPECT_EQ(imageFingerprint(config.output), 6'504'118'807'975'186'671ull);
}

TEST(DriveSimulation, TheRealisticCameraExposesEachFrameUnderAutoExposure) {
  DriveSimulationConfig config = shortDelftDrive("realistic");
  config.duration_s = 1.0;
  simulateDrive(config);
  const fs::path root(config.output);
  std::istringstream rows(readAll(root / "cam0" / "exposure.csv"));
  std::string row;
  std::getline(rows, row);
  EXPECT_EQ(row, "#timestamp [ns],exposure_time [s],gain [dB]");
  int frames = 0;
  while (std::getline(rows, row)) {
    ++frames;
    const auto [stamp, exposure_time_s, gain_db] = exposureRow(row);
    EXPECT_GE(std::stod(exposure_time_s), config.auto_exposure.min_exposure_time_s) << row;
    EXPECT_LE(std::stod(exposure_time_s), config.auto_exposure.max_exposure_time_s) << row;
    EXPECT_GE(std::stod(gain_db), 0.0) << row;
    // Auto-exposure settled on the first view and meters the noise-free
    // render at the stamp: the image's mean is within the deadband, give or
    // take what blur and noise move it (well under 1 DN over 307,200 pixels).
    const cv::Mat image =
        cv::imread((root / "cam0" / "data" / (stamp + ".png")).string(), cv::IMREAD_UNCHANGED);
    ASSERT_FALSE(image.empty()) << stamp;
    EXPECT_NEAR(cv::mean(image)[0], config.auto_exposure.target_mean_dn,
                config.auto_exposure.tolerance * config.auto_exposure.target_mean_dn + 1.0)
        << row;
  }
  EXPECT_EQ(frames, 3);
}

// The 8-bit image a dataset wrote at camera stamp `stamp`.
cv::Mat datasetImage(const fs::path& root, const std::string& stamp) {
  return cv::imread((root / "cam0" / "data" / (stamp + ".png")).string(), cv::IMREAD_UNCHANGED);
}

// The camera stamps of a dataset's images, in order.
std::vector<std::string> imageStamps(const fs::path& root) {
  std::vector<std::string> stamps;
  for (const auto& entry : fs::directory_iterator(root / "cam0" / "data")) {
    stamps.push_back(entry.path().stem().string());
  }
  std::sort(stamps.begin(), stamps.end());
  return stamps;
}

// Gain (dB) of each frame of a realistic camera's dataset, by camera stamp.
std::map<std::string, double> frameGains_db(const fs::path& root) {
  std::istringstream rows(readAll(root / "cam0" / "exposure.csv"));
  std::string row;
  std::getline(rows, row);
  std::map<std::string, double> gains_db;
  while (std::getline(rows, row)) {
    const auto [stamp, exposure_time_s, gain_db] = exposureRow(row);
    gains_db[stamp] = std::stod(gain_db);
  }
  return gains_db;
}

// Mean, variance and fourth central moment of the DN of a pixel that no
// light reaches: y = clamp(round(s z), 0, 255), z standard normal, s = K
// read_noise_e the dark noise in DN (CameraSensor's model with mu_e = 0).
struct DarkMoments {
  double mean = 0.0;
  double variance = 0.0;
  double fourth = 0.0;
};

DarkMoments darkMoments(double sigma_dn) {
  const auto below = [sigma_dn](double y) {
    return 0.5 * std::erfc(-y / sigma_dn / std::sqrt(2.0));
  };
  std::vector<double> p(256, 0.0);
  for (int y = 1; y < 255; ++y) {
    p[y] = below(y + 0.5) - below(y - 0.5);
  }
  p[255] = 1.0 - below(254.5);
  p[0] = below(0.5);
  DarkMoments moments;
  for (int y = 0; y < 256; ++y) {
    moments.mean += y * p[y];
  }
  for (int y = 0; y < 256; ++y) {
    const double d = y - moments.mean;
    moments.variance += d * d * p[y];
    moments.fourth += d * d * d * d * p[y];
  }
  return moments;
}

// A lens covered from 1.2 s to 2.7 s of a drive filmed at 2 Hz: the frames at
// 1.5, 2.0 and 2.5 s (exposures of at most 2 ms about their stamps) hold only
// the sensor's dark noise at the gain auto-exposure set, whose mean and
// variance follow from the sensor model; the frames before the window are
// the uncovered drive's, byte for byte; auto-exposure, metering the dark,
// turns the first frame after the window brighter than the uncovered one.
TEST(DriveSimulation, CoveredLensFramesHoldOnlyTheSensorsDarkNoise) {
  DriveSimulationConfig open = shortDelftDrive("uncovered");
  open.duration_s = 3.0;
  DriveSimulationConfig covered = shortDelftDrive("covered");
  covered.duration_s = open.duration_s;
  covered.lens_cover.emplace(1.2, 1.5);
  EXPECT_EQ(simulateDrive(covered).images, simulateDrive(open).images);
  const std::vector<std::string> stamps = imageStamps(covered.output);
  ASSERT_EQ(stamps, imageStamps(open.output));
  ASSERT_EQ(stamps.size(), 7u);
  const std::map<std::string, double> gains_db = frameGains_db(covered.output);
  const CameraSensor sensor(CameraRays(opencvSampleCamera()), covered.sensor);
  for (size_t i = 0; i < stamps.size(); ++i) {
    SCOPED_TRACE("frame " + stamps[i]);
    const cv::Mat image = datasetImage(covered.output, stamps[i]);
    const cv::Mat uncovered = datasetImage(open.output, stamps[i]);
    ASSERT_FALSE(image.empty());
    ASSERT_FALSE(uncovered.empty());
    cv::Scalar mean;
    cv::Scalar sigma;
    cv::meanStdDev(image, mean, sigma);
    cv::Scalar uncovered_mean;
    cv::Scalar uncovered_sigma;
    cv::meanStdDev(uncovered, uncovered_mean, uncovered_sigma);
    // The uncovered drive sees a street: a wide spread of grey levels.
    EXPECT_GT(uncovered_sigma[0], 25.0);
    if (i < 3) {
      EXPECT_EQ(cv::norm(image, uncovered, cv::NORM_INF), 0.0);
    } else if (i < 6) {
      ASSERT_EQ(gains_db.count(stamps[i]), 1u);
      const double gain_db = gains_db.at(stamps[i]);
      const DarkMoments dark =
          darkMoments(sensor.systemGain_dn_per_e(gain_db) * covered.sensor.read_noise_e);
      const double n = static_cast<double>(image.total());
      // Five standard errors: sqrt(variance / n) for the mean, sqrt((mu_4 -
      // variance^2) / n) for the variance; one pixel's worth of slack.
      EXPECT_NEAR(mean[0], dark.mean, 5.0 * std::sqrt(dark.variance / n) + 1.0 / n)
          << "gain " << gain_db << " dB";
      EXPECT_NEAR(sigma[0] * sigma[0], dark.variance,
                  5.0 * std::sqrt((dark.fourth - dark.variance * dark.variance) / n) + 1.0 / n)
          << "gain " << gain_db << " dB";
    } else {
      EXPECT_GT(mean[0], uncovered_mean[0] + 10.0);
    }
  }
}

// The ideal camera's covered frames are black; a frame whose exposure (8 ms)
// the cover's edge cuts gets the open share of its light (its image is
// round(f 255 radiance) without noise); every other frame is unchanged.
TEST(DriveSimulation, CoveredLensBlackensTheIdealCamerasFramesAndNoOthers) {
  DriveSimulationConfig open = shortDelftDrive("ideal_uncovered");
  open.duration_s = 3.0;
  open.ideal_camera = true;
  open.noise_sigma = 0.0;
  DriveSimulationConfig covered = open;
  covered.output = shortDelftDrive("ideal_covered").output;
  // Frame 1.5 s is exposed 1.496-1.504 s: 6 ms covered, f = 0.25. Frame
  // 2.5 s: covered until 2.498 s, f = 0.75.
  covered.lens_cover.emplace(1.498, 1.0);
  simulateDrive(open);
  simulateDrive(covered);
  const std::vector<std::string> stamps = imageStamps(covered.output);
  ASSERT_EQ(stamps, imageStamps(open.output));
  ASSERT_EQ(stamps.size(), 7u);
  const std::map<size_t, double> open_fractions = {{3, 0.25}, {4, 0.0}, {5, 0.75}};
  for (size_t i = 0; i < stamps.size(); ++i) {
    SCOPED_TRACE("frame " + stamps[i]);
    const cv::Mat image = datasetImage(covered.output, stamps[i]);
    const cv::Mat uncovered = datasetImage(open.output, stamps[i]);
    ASSERT_FALSE(image.empty());
    ASSERT_FALSE(uncovered.empty());
    const auto fraction = open_fractions.find(i);
    if (fraction == open_fractions.end()) {
      EXPECT_EQ(cv::norm(image, uncovered, cv::NORM_INF), 0.0);
      continue;
    }
    // |round(f x) - f round(x)| <= 1/2 + f/2 for x = 255 radiance.
    cv::Mat scaled;
    uncovered.convertTo(scaled, CV_32F, fraction->second);
    cv::Mat lit;
    image.convertTo(lit, CV_32F);
    EXPECT_LE(cv::norm(lit, scaled, cv::NORM_INF), 0.5 + 0.5 * fraction->second + 1e-3);
    if (fraction->second == 0.0) {
      EXPECT_EQ(cv::countNonZero(image), 0);
    }
  }
}

TEST(DriveSimulation, InvalidCameraOptionsAreNamed) {
  DriveSimulationConfig config = shortDelftDrive("bad_sensor");
  config.sensor.read_noise_e = -2.0;
  try {
    simulateDrive(config);
    FAIL();
  } catch (const std::invalid_argument& error) {
    EXPECT_NE(std::string(error.what()).find("read_noise_e must be >= 0 (got -2)"),
              std::string::npos)
        << error.what();
  }
  config = shortDelftDrive("bad_auto_exposure");
  config.auto_exposure.max_gain_db = -6.0;
  EXPECT_THROW(simulateDrive(config), std::invalid_argument);
}

TEST(DriveSimulation, MissingCityModelIsNamed) {
  DriveSimulationConfig config = shortDelftDrive("missing");
  config.city_model = "no_such_city.json";
  try {
    simulateDrive(config);
    FAIL();
  } catch (const std::runtime_error& error) {
    EXPECT_NE(std::string(error.what()).find("no_such_city.json"), std::string::npos);
  }
}

}  // namespace
}  // namespace lineloc
