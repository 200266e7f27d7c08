#include "common/trajectory/tum_trajectory.h"

#include <fmt/format.h>

#include <array>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "common/trajectory/line_records.h"

namespace lineloc {
namespace {

constexpr int kFieldCount = 8;
constexpr double kQuaternionNormTolerance = 1e-3;

// Seconds with 9 decimals -> nanoseconds, without the rounding of a double.
int64_t parseSecondsToNs(const std::string& text, const std::string& where) {
  const auto dot = text.find('.');
  const bool negative = !text.empty() && text[0] == '-';
  const std::string whole = text.substr(negative ? 1 : 0, dot - (negative ? 1 : 0));
  std::string fraction = dot == std::string::npos ? "" : text.substr(dot + 1);
  if (whole.empty() || fraction.size() > 9 ||
      whole.find_first_not_of("0123456789") != std::string::npos ||
      fraction.find_first_not_of("0123456789") != std::string::npos) {
    throw std::runtime_error(fmt::format("{}: time '{}' is not a decimal number", where, text));
  }
  // |seconds| <= 9.2e9 keeps seconds * 1e9 + nanos inside int64 (year 2262).
  constexpr int64_t kMaxSeconds = std::numeric_limits<int64_t>::max() / 1'000'000'000 - 1;
  const int64_t seconds = whole.size() > 10 ? kMaxSeconds + 1 : std::stoll(whole);
  if (seconds > kMaxSeconds) {
    throw std::runtime_error(fmt::format("{}: time '{}' is out of range", where, text));
  }
  fraction.resize(9, '0');
  const int64_t ns = seconds * 1'000'000'000 + std::stoll(fraction);
  return negative ? -ns : ns;
}

}  // namespace

TumWriter::TumWriter(const std::string& path) : path_(path), stream_(path) {
  if (!stream_) {
    throw std::runtime_error(fmt::format("cannot open trajectory file '{}' for writing", path));
  }
  stream_ << "# t tx ty tz qx qy qz qw\n";
}

void TumWriter::write(const StampedPose& stamped) {
  stream_ << formatTumLine(stamped) << '\n';
  stream_.flush();
}

std::string formatTumLine(const StampedPose& stamped) {
  const Eigen::Vector3d t = stamped.pose.translation();
  const Eigen::Quaterniond q(stamped.pose.linear());
  const int64_t abs_ns = std::llabs(stamped.stamp_ns);
  return fmt::format("{}{}.{:09d} {:.6f} {:.6f} {:.6f} {:.9f} {:.9f} {:.9f} {:.9f}",
                     stamped.stamp_ns < 0 ? "-" : "", abs_ns / 1'000'000'000,
                     abs_ns % 1'000'000'000, t.x(), t.y(), t.z(), q.x(), q.y(), q.z(), q.w());
}

StampedPose parseTumLine(const std::string& line, const std::string& where) {
  std::istringstream fields(line);
  std::string time_text;
  fields >> time_text;
  std::array<double, kFieldCount - 1> values{};
  for (double& value : values) {
    if (!(fields >> value)) {
      throw std::runtime_error(
          fmt::format("{}: expected {} numbers 't tx ty tz qx qy qz qw'", where, kFieldCount));
    }
    if (!std::isfinite(value)) {
      throw std::runtime_error(fmt::format("{}: non-finite value", where));
    }
  }
  std::string extra;
  if (fields >> extra) {
    throw std::runtime_error(fmt::format("{}: more than {} fields", where, kFieldCount));
  }
  const Eigen::Quaterniond q(values[6], values[3], values[4], values[5]);
  if (std::abs(q.norm() - 1.0) > kQuaternionNormTolerance) {
    throw std::runtime_error(fmt::format("{}: quaternion norm {} is not 1", where, q.norm()));
  }
  StampedPose stamped;
  stamped.stamp_ns = parseSecondsToNs(time_text, where);
  stamped.pose.linear() = q.normalized().toRotationMatrix();
  stamped.pose.translation() = Eigen::Vector3d(values[0], values[1], values[2]);
  return stamped;
}

StampedPose parseTumFields(const std::vector<std::string>& fields, const std::string& where) {
  std::string line;
  for (int i = 0; i < kFieldCount; ++i) {
    line += fields.at(static_cast<size_t>(i)) + ' ';
  }
  return parseTumLine(line, where);
}

std::vector<StampedPose> readTumFile(const std::string& path) {
  return readLineRecords<StampedPose>(path, "trajectory file", parseTumLine);
}

}  // namespace lineloc
