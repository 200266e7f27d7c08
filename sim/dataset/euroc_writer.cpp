#include "sim/dataset/euroc_writer.h"

#include <fmt/format.h>

#include <filesystem>
#include <opencv2/imgcodecs.hpp>
#include <stdexcept>

namespace lineloc {
namespace {

namespace fs = std::filesystem;

std::string prepareRoot(const std::string& root) {
  std::error_code error;
  if (fs::exists(root, error) && !fs::is_empty(root, error)) {
    throw std::runtime_error(fmt::format("dataset folder '{}' exists and is not empty", root));
  }
  for (const char* folder :
       {"cam0/data", "imu0", "gps0", "compass0", "state_groundtruth_estimate0"}) {
    fs::create_directories(fs::path(root) / folder, error);
    if (error) {
      throw std::runtime_error(fmt::format("cannot create '{}': {}",
                                           (fs::path(root) / folder).string(), error.message()));
    }
  }
  return root;
}

// EuRoC's T_BS block: a 4x4 row-major matrix.
std::string transformYaml(const Eigen::Isometry3d& T) {
  std::string data;
  for (int row = 0; row < 4; ++row) {
    for (int col = 0; col < 4; ++col) {
      data += fmt::format("{}{:.12f}", row + col == 0 ? "" : ", ", T.matrix()(row, col));
    }
  }
  return fmt::format("T_BS:\n  cols: 4\n  rows: 4\n  data: [{}]\n", data);
}

void writeText(const fs::path& path, const std::string& text) {
  std::ofstream file(path, std::ios::binary);
  file << text;
  if (!file) {
    throw std::runtime_error(fmt::format("cannot write '{}'", path.string()));
  }
}

void writeCameraFiles(const fs::path& folder, const EurocDatasetSpec& spec) {
  const PinholeCamera& camera = spec.camera.camera;
  std::vector<double> distortion = spec.camera.distortion;
  distortion.resize(std::max<size_t>(distortion.size(), 4), 0.0);
  writeText(
      folder / "sensor.yaml",
      fmt::format("sensor_type: camera\n"
                  "comment: lineloc-sim rendered camera, its lens model as calibration.yaml "
                  "holds it\n"
                  "{}rate_hz: {:.6f}\nresolution: [{}, {}]\ncamera_model: pinhole\n"
                  "intrinsics: [{:.9f}, {:.9f}, {:.9f}, {:.9f}]\n"
                  "distortion_model: {}\n"
                  "distortion_coefficients: [{:.17g}]\n",
                  transformYaml(spec.T_body_camera), spec.camera_rate_hz, camera.width,
                  camera.height, camera.fx, camera.fy, camera.cx, camera.cy,
                  spec.camera.lens == LensModel::kEquidistant ? "equidistant" : "radial-tangential",
                  fmt::join(distortion, ", ")));
  writeCameraCalibration((folder / "calibration.yaml").string(), spec.camera);
}

void writeImuFile(const fs::path& folder, const EurocDatasetSpec& spec) {
  const EurocImuSpec& imu = spec.imu;
  writeText(folder / "sensor.yaml",
            fmt::format("sensor_type: imu\ncomment: lineloc-sim synthetic IMU\n{}rate_hz: {:.6f}\n"
                        "gyroscope_noise_density: {:.9e}\ngyroscope_random_walk: {:.9e}\n"
                        "accelerometer_noise_density: {:.9e}\naccelerometer_random_walk: {:.9e}\n",
                        transformYaml(spec.T_body_imu), imu.rate_hz, imu.gyroscope_noise_density,
                        imu.gyroscope_random_walk, imu.accelerometer_noise_density,
                        imu.accelerometer_random_walk));
}

}  // namespace

EurocWriter::EurocWriter(const std::string& root, const EurocDatasetSpec& spec)
    : root_(prepareRoot(root)),
      camera_ground_truth_((fs::path(root) / "groundtruth_cam0.tum").string()) {
  open(images_, "cam0/data.csv", "#timestamp [ns],filename");
  open(imu_, "imu0/data.csv",
       "#timestamp [ns],w_RS_S_x [rad s^-1],w_RS_S_y [rad s^-1],w_RS_S_z [rad s^-1],"
       "a_RS_S_x [m s^-2],a_RS_S_y [m s^-2],a_RS_S_z [m s^-2]");
  open(gps_, "gps0/data.csv", "#timestamp [ns],sentence");
  open(compass_, "compass0/data.csv", "#timestamp [ns],heading [rad]");
  open(ground_truth_, "state_groundtruth_estimate0/data.csv",
       "#timestamp, p_RS_R_x [m], p_RS_R_y [m], p_RS_R_z [m], q_RS_w [], q_RS_x [], q_RS_y [], "
       "q_RS_z [], v_RS_R_x [m s^-1], v_RS_R_y [m s^-1], v_RS_R_z [m s^-1], "
       "b_w_RS_S_x [rad s^-1], b_w_RS_S_y [rad s^-1], b_w_RS_S_z [rad s^-1], "
       "b_a_RS_S_x [m s^-2], b_a_RS_S_y [m s^-2], b_a_RS_S_z [m s^-2]");
  camera_truth_stamps_.name = (fs::path(root) / "groundtruth_cam0.tum").string();
  nmea_.open(fs::path(root) / "gps0" / "nmea.txt", std::ios::binary);
  writeCameraFiles(fs::path(root) / "cam0", spec);
  writeImuFile(fs::path(root) / "imu0", spec);
}

void EurocWriter::open(Stream& stream, const std::string& relative_path,
                       const std::string& header) {
  stream.name = (fs::path(root_) / relative_path).string();
  stream.file.open(stream.name, std::ios::binary);
  if (!stream.file) {
    throw std::runtime_error(fmt::format("cannot write '{}'", stream.name));
  }
  stream.file << header << '\n';
}

void EurocWriter::checkStamp(Stream& stream, int64_t stamp_ns) {
  if (stamp_ns <= stream.last_stamp_ns) {
    throw std::invalid_argument(fmt::format("{}: time stamp {} ns does not follow {} ns",
                                            stream.name, stamp_ns, stream.last_stamp_ns));
  }
  stream.last_stamp_ns = stamp_ns;
}

void EurocWriter::writeImage(int64_t stamp_ns, const cv::Mat& image) {
  checkStamp(images_, stamp_ns);
  const std::string file_name = fmt::format("{}.png", stamp_ns);
  const std::string path = (fs::path(root_) / "cam0" / "data" / file_name).string();
  if (!cv::imwrite(path, image)) {
    throw std::runtime_error(fmt::format("cannot write image '{}'", path));
  }
  images_.file << stamp_ns << ',' << file_name << '\n';
}

void EurocWriter::writeCameraGroundTruth(const StampedPose& T_world_camera) {
  checkStamp(camera_truth_stamps_, T_world_camera.stamp_ns);
  camera_ground_truth_.write(T_world_camera);
}

void EurocWriter::writeImu(int64_t stamp_ns, const Eigen::Vector3d& angular_velocity_rad_s,
                           const Eigen::Vector3d& acceleration_m_s2) {
  checkStamp(imu_, stamp_ns);
  const Eigen::Vector3d& w = angular_velocity_rad_s;
  const Eigen::Vector3d& a = acceleration_m_s2;
  imu_.file << fmt::format("{},{:.9f},{:.9f},{:.9f},{:.9f},{:.9f},{:.9f}\n", stamp_ns, w.x(), w.y(),
                           w.z(), a.x(), a.y(), a.z());
}

void EurocWriter::writeNmea(int64_t stamp_ns, const std::string& sentence) {
  checkStamp(gps_, stamp_ns);
  if (sentence.find_first_of("\"\r\n") != std::string::npos) {
    throw std::invalid_argument(
        fmt::format("{}: NMEA sentence with a quote or line break: '{}'", gps_.name, sentence));
  }
  // NMEA fields contain commas: the sentence is one quoted csv field.
  gps_.file << stamp_ns << ",\"" << sentence << "\"\n";
  nmea_ << sentence << "\r\n";
}

void EurocWriter::writeCompass(int64_t stamp_ns, double heading_rad) {
  checkStamp(compass_, stamp_ns);
  compass_.file << fmt::format("{},{:.9f}\n", stamp_ns, heading_rad);
}

void EurocWriter::writeGroundTruth(const EurocGroundTruth& state) {
  checkStamp(ground_truth_, state.stamp_ns);
  const Eigen::Vector3d& p = state.T_world_body.translation();
  const Eigen::Quaterniond q(state.T_world_body.linear());
  const Eigen::Vector3d& v = state.velocity_world;
  const Eigen::Vector3d& bw = state.gyro_bias;
  const Eigen::Vector3d& ba = state.accel_bias;
  ground_truth_.file << fmt::format(
      "{},{:.9f},{:.9f},{:.9f},{:.12f},{:.12f},{:.12f},{:.12f},{:.9f},{:.9f},{:.9f},"
      "{:.12f},{:.12f},{:.12f},{:.12f},{:.12f},{:.12f}\n",
      state.stamp_ns, p.x(), p.y(), p.z(), q.w(), q.x(), q.y(), q.z(), v.x(), v.y(), v.z(), bw.x(),
      bw.y(), bw.z(), ba.x(), ba.y(), ba.z());
}

}  // namespace lineloc
