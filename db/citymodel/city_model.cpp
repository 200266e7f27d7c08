#include "db/citymodel/city_model.h"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <string_view>

namespace lineloc::citymodel {
namespace {

constexpr size_t kMaxKeptMessages = 20;
constexpr size_t kMaxEpsgDigits = 9;

// Removes `prefix` from the front of `text` when it is there (ignoring case).
bool consumePrefix(std::string_view& text, std::string_view prefix) {
  const bool match = text.size() >= prefix.size() &&
                     std::equal(prefix.begin(), prefix.end(), text.begin(), [](char a, char b) {
                       return std::tolower(static_cast<unsigned char>(a)) ==
                              std::tolower(static_cast<unsigned char>(b));
                     });
  if (match) {
    text.remove_prefix(prefix.size());
  }
  return match;
}

// Removes a version ([0-9.]*, at least one character unless `may_be_empty`)
// and the `separator` after it from the front of `text`.
bool consumeVersion(std::string_view& text, char separator, bool may_be_empty) {
  const size_t end = text.find_first_not_of("0123456789.");
  if (end == std::string_view::npos || text[end] != separator || (end == 0 && !may_be_empty)) {
    return false;
  }
  text.remove_prefix(end + 1);
  return true;
}

// The digits of the EPSG code once the prefix is removed, or empty when the
// string is none of the accepted forms.
std::string_view epsgDigits(std::string_view crs) {
  const bool prefixed =
      consumePrefix(crs, "EPSG:") ||
      (consumePrefix(crs, "urn:ogc:def:crs:EPSG:") && consumeVersion(crs, ':', true)) ||
      ((consumePrefix(crs, "http://") || consumePrefix(crs, "https://")) &&
       consumePrefix(crs, "www.opengis.net/def/crs/EPSG/") && consumeVersion(crs, '/', false));
  const bool digits = !crs.empty() && crs.size() <= kMaxEpsgDigits &&
                      crs.find_first_not_of("0123456789") == std::string_view::npos;
  return prefixed && digits ? crs : std::string_view();
}

}  // namespace

void SkippedObjects::add(const std::string& reason, const std::string& message) {
  ++count_by_reason[reason];
  if (messages.size() < kMaxKeptMessages) {
    messages.push_back(message);
  }
}

int SkippedObjects::total() const {
  int total = 0;
  for (const auto& [reason, count] : count_by_reason) {
    total += count;
  }
  return total;
}

namespace {

std::string describe(const std::string& source, const std::string& object_id,
                     const std::string& reason, const std::string& detail) {
  std::string message = source;
  if (!object_id.empty()) {
    message += fmt::format(": object '{}'", object_id);
  }
  message += ": " + reason;
  if (!detail.empty()) {
    message += " (" + detail + ")";
  }
  return message;
}

}  // namespace

ModelError::ModelError(const std::string& source, const std::string& object_id,
                       const std::string& reason, const std::string& detail)
    : std::runtime_error(describe(source, object_id, reason, detail)), reason_(reason) {}

void handleInvalidObject(const ModelError& error, InvalidObjectPolicy policy,
                         SkippedObjects& skipped) {
  if (policy == InvalidObjectPolicy::kAbort) {
    throw error;
  }
  skipped.add(error.reason(), error.what());
}

Eigen::Vector3d zUpPoint(const Eigen::Vector3d& file_point, UpAxis up_axis) {
  return up_axis == UpAxis::kZ ? file_point
                               : Eigen::Vector3d(file_point.x(), -file_point.z(), file_point.y());
}

UpAxis parseUpAxis(const std::string& axis) {
  if (axis == "z") {
    return UpAxis::kZ;
  }
  if (axis == "y") {
    return UpAxis::kY;
  }
  throw std::invalid_argument(fmt::format("unknown up axis '{}': expected z or y", axis));
}

int parseEpsgCode(const std::string& crs) {
  const std::string_view digits = epsgDigits(crs);
  if (digits.empty()) {
    throw std::invalid_argument(fmt::format(
        "unknown CRS '{}': expected EPSG:N, urn:ogc:def:crs:EPSG::N or an opengis.net EPSG URL",
        crs));
  }
  int code = 0;
  std::from_chars(digits.data(), digits.data() + digits.size(), code);
  if (code <= 0) {
    throw std::invalid_argument(fmt::format("unknown CRS '{}': EPSG code must be positive", crs));
  }
  return code;
}

}  // namespace lineloc::citymodel
