#include "db/citymodel/city_model.h"

#include <fmt/format.h>

#include <charconv>
#include <regex>

namespace lineloc::citymodel {
namespace {

constexpr size_t kMaxKeptMessages = 20;

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

int parseEpsgCode(const std::string& crs) {
  static const std::regex kPatterns(
      R"(^(?:EPSG:|urn:ogc:def:crs:EPSG:[0-9.]*:|https?://www\.opengis\.net/def/crs/EPSG/[0-9.]+/)([0-9]{1,9})$)",
      std::regex::icase);
  std::smatch match;
  if (!std::regex_match(crs, match, kPatterns)) {
    throw std::invalid_argument(fmt::format(
        "unknown CRS '{}': expected EPSG:N, urn:ogc:def:crs:EPSG::N or an opengis.net EPSG URL",
        crs));
  }
  const std::string digits = match[1].str();
  int code = 0;
  std::from_chars(digits.data(), digits.data() + digits.size(), code);
  if (code <= 0) {
    throw std::invalid_argument(fmt::format("unknown CRS '{}': EPSG code must be positive", crs));
  }
  return code;
}

}  // namespace lineloc::citymodel
