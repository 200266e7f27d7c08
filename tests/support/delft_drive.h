// The bundled Delft city model and simulated drives through it, as the tests
// and benchmarks of the whole system use them: the model file, the site frame
// and camera height of the README's demo (deploy/demo.sh), and a simulated
// drive read back as its frames with their true camera poses.
#pragma once

#include <Eigen/Geometry>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "common/camera/camera_calibration.h"
#include "sim/dataset/drive_simulation.h"

namespace lineloc::test {

inline constexpr double kDelftCameraHeightM = 1.5;
// When the demo's drive starts (deploy/demo.sh): a sunny April morning.
inline constexpr const char* kDelftDriveStartUtc = "2026-04-14T09:30:00Z";

// data/citymodels/delft.json, bundled with lineloc.
std::filesystem::path delftCityModel();

// Model coordinates (EPSG:7415) of the site origin: the site frame is the
// model's CRS minus this.
Eigen::Vector3d delftSiteOrigin();

// The origin as command-line words: x y z.
std::vector<std::string> delftSiteOriginArgs();

struct SimulatedFrames {
  CameraCalibration calibration;
  std::vector<std::string> images;
  std::vector<int64_t> stamps_ns;
  // T_world_camera at each frame's exposure.
  std::vector<Eigen::Isometry3d> truth;
};

// Simulates `config` through the Delft model (its city model, site origin and
// camera height are set here) into `folder`, and reads the frames back.
SimulatedFrames simulateDelftDrive(DriveSimulationConfig config,
                                   const std::filesystem::path& folder);

}  // namespace lineloc::test
