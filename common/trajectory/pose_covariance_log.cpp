#include "common/trajectory/pose_covariance_log.h"

#include <fmt/format.h>

#include <Eigen/Cholesky>
#include <stdexcept>

#include "common/trajectory/line_records.h"
#include "common/trajectory/tum_trajectory.h"

namespace lineloc {
namespace {

constexpr size_t kTumFields = 8;
constexpr size_t kCovarianceFields = 21;

}  // namespace

PoseCovarianceLogWriter::PoseCovarianceLogWriter(const std::string& path) : stream_(path) {
  if (!stream_) {
    throw std::runtime_error(fmt::format("cannot open pose log '{}' for writing", path));
  }
  stream_ << "# t tx ty tz qx qy qz qw covariance upper triangle c00 c01 .. c55 (m, rad; e = "
             "[dp; dtheta])\n";
}

void PoseCovarianceLogWriter::write(const StampedPoseWithCovariance& stamped) {
  stream_ << formatPoseCovarianceLine(stamped) << '\n';
  stream_.flush();
}

std::string formatPoseCovarianceLine(const StampedPoseWithCovariance& stamped) {
  return formatTumLine({stamped.stamp_ns, stamped.pose.pose}) +
         formatCovarianceFields(stamped.pose.covariance);
}

StampedPoseWithCovariance parsePoseCovarianceLine(const std::string& line,
                                                  const std::string& where) {
  const std::vector<std::string> fields = splitFields(line);
  if (fields.size() != kTumFields + kCovarianceFields) {
    throw std::runtime_error(
        fmt::format("{}: expected {} fields (a TUM pose and 21 covariance entries), got {}", where,
                    kTumFields + kCovarianceFields, fields.size()));
  }
  const StampedPose stamped = parseTumFields(fields, where);
  StampedPoseWithCovariance parsed;
  parsed.stamp_ns = stamped.stamp_ns;
  parsed.pose.pose = stamped.pose;
  parsed.pose.covariance = parseCovarianceFields(fields, kTumFields, where);
  return parsed;
}

std::vector<StampedPoseWithCovariance> readPoseCovarianceLog(const std::string& path) {
  return readLineRecords<StampedPoseWithCovariance>(path, "pose log", parsePoseCovarianceLine);
}

std::string formatCovarianceFields(const Matrix6d& covariance) {
  std::string text;
  for (int row = 0; row < 6; ++row) {
    for (int col = row; col < 6; ++col) {
      text += fmt::format(" {:.9g}", covariance(row, col));
    }
  }
  return text;
}

Matrix6d parseCovarianceFields(const std::vector<std::string>& fields, size_t first,
                               const std::string& where) {
  Matrix6d covariance;
  size_t field = first;
  for (int row = 0; row < 6; ++row) {
    for (int col = row; col < 6; ++col) {
      const double value = parseFinite(fields.at(field++), "covariance entry", where);
      covariance(row, col) = value;
      covariance(col, row) = value;
    }
  }
  if (covariance.llt().info() != Eigen::Success) {
    throw std::runtime_error(fmt::format("{}: covariance is not positive definite", where));
  }
  return covariance;
}

}  // namespace lineloc
