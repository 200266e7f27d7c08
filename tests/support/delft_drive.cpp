#include "tests/support/delft_drive.h"

#include <fmt/format.h>

#include <map>

#include "common/trajectory/tum_trajectory.h"
#include "robot/input/image_sequence.h"

namespace lineloc::test {

std::filesystem::path delftCityModel() {
  return std::filesystem::path(LINELOC_SOURCE_DIR) / "data" / "citymodels" / "delft.json";
}

Eigen::Vector3d delftSiteOrigin() {
  return {84900.0, 447600.0, 0.0};
}

std::vector<std::string> delftSiteOriginArgs() {
  const Eigen::Vector3d origin = delftSiteOrigin();
  return {fmt::format("{}", origin.x()), fmt::format("{}", origin.y()),
          fmt::format("{}", origin.z())};
}

SimulatedFrames simulateDelftDrive(DriveSimulationConfig config,
                                   const std::filesystem::path& folder) {
  const Eigen::Vector3d origin = delftSiteOrigin();
  config.city_model = delftCityModel().string();
  config.site_origin = {origin.x(), origin.y(), origin.z()};
  config.camera_height_m = kDelftCameraHeightM;
  config.output = folder.string();
  simulateDrive(config);
  SimulatedFrames frames;
  frames.calibration = readCameraCalibration((folder / "cam0" / "calibration.yaml").string());
  std::map<int64_t, Eigen::Isometry3d> truth;
  for (const StampedPose& pose : readTumFile((folder / "groundtruth_cam0.tum").string())) {
    truth[pose.stamp_ns] = pose.pose;
  }
  for (const FrameRef& frame : listImageSequence((folder / "cam0").string())) {
    frames.images.push_back(frame.path);
    frames.stamps_ns.push_back(*frame.stamp_ns);
    frames.truth.push_back(truth.at(*frame.stamp_ns));
  }
  return frames;
}

}  // namespace lineloc::test
