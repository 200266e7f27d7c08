#include "common/trajectory/fix_log.h"

#include <fmt/format.h>

#include <charconv>
#include <stdexcept>

#include "common/trajectory/line_records.h"
#include "common/trajectory/pose_covariance_log.h"
#include "common/trajectory/tum_trajectory.h"

namespace lineloc {
namespace {

constexpr int kTumFields = 8;
constexpr int kCovarianceFields = 21;
constexpr int kFieldCount = kTumFields + 9 + kCovarianceFields;

uint32_t parseCount(const std::string& text, const char* name, const std::string& where) {
  uint32_t value = 0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (error != std::errc() || end != text.data() + text.size()) {
    throw std::runtime_error(
        fmt::format("{}: {} '{}' is not an unsigned integer", where, name, text));
  }
  return value;
}

double parseNonNegative(const std::string& text, const char* name, const std::string& where) {
  const double value = parseFinite(text, name, where);
  if (value < 0.0) {
    throw std::runtime_error(fmt::format("{}: {} is negative", where, name));
  }
  return value;
}

bool isStatusName(const std::string& text) {
  return !text.empty() &&
         text.find_first_not_of("abcdefghijklmnopqrstuvwxyz_") == std::string::npos;
}

}  // namespace

FixLogWriter::FixLogWriter(const std::string& path) : stream_(path) {
  if (!stream_) {
    throw std::runtime_error(fmt::format("cannot open fix log '{}' for writing", path));
  }
  stream_ << "# t tx ty tz qx qy qz qw status inliers model_lines residual_rms_px latency_ms "
             "front_end_ms to_backbone_ms backbone_ms back_ms covariance upper triangle c00 c01 "
             ".. c55 (m, rad; e = [dp; dtheta])\n";
}

void FixLogWriter::write(const LoggedFix& fix) {
  stream_ << formatFixLogLine(fix) << '\n';
  stream_.flush();
}

std::string formatFixLogLine(const LoggedFix& fix) {
  std::string line = formatTumLine({fix.stamp_ns, fix.T_world_camera.pose});
  line += fmt::format(" {} {} {} {:.3f} {:.3f} {:.3f} {:.3f} {:.3f} {:.3f}", fix.status,
                      fix.inliers, fix.model_lines, fix.residual_rms_px, fix.latency_ms,
                      fix.front_end_ms, fix.to_backbone_ms, fix.backbone_ms, fix.back_ms);
  return line + formatCovarianceFields(fix.T_world_camera.covariance);
}

LoggedFix parseFixLogLine(const std::string& line, const std::string& where) {
  const std::vector<std::string> fields = splitFields(line);
  if (static_cast<int>(fields.size()) != kFieldCount) {
    throw std::runtime_error(fmt::format(
        "{}: expected {} fields (a TUM pose, status, inliers, model_lines, residual_rms_px, "
        "latency_ms, its four legs and 21 covariance entries), got {}",
        where, kFieldCount, fields.size()));
  }
  const StampedPose stamped = parseTumFields(fields, where);
  LoggedFix fix;
  fix.stamp_ns = stamped.stamp_ns;
  fix.T_world_camera.pose = stamped.pose;
  fix.status = fields[kTumFields];
  if (!isStatusName(fix.status)) {
    throw std::runtime_error(
        fmt::format("{}: status '{}' is not a status name", where, fix.status));
  }
  fix.inliers = parseCount(fields[kTumFields + 1], "inliers", where);
  fix.model_lines = parseCount(fields[kTumFields + 2], "model_lines", where);
  fix.residual_rms_px = parseNonNegative(fields[kTumFields + 3], "residual_rms_px", where);
  fix.latency_ms = parseNonNegative(fields[kTumFields + 4], "latency_ms", where);
  fix.front_end_ms = parseNonNegative(fields[kTumFields + 5], "front_end_ms", where);
  fix.to_backbone_ms = parseFinite(fields[kTumFields + 6], "to_backbone_ms", where);
  fix.backbone_ms = parseNonNegative(fields[kTumFields + 7], "backbone_ms", where);
  fix.back_ms = parseFinite(fields[kTumFields + 8], "back_ms", where);
  fix.T_world_camera.covariance = parseCovarianceFields(fields, kTumFields + 9, where);
  return fix;
}

std::vector<LoggedFix> readFixLog(const std::string& path) {
  return readLineRecords<LoggedFix>(path, "fix log", parseFixLogLine);
}

}  // namespace lineloc
