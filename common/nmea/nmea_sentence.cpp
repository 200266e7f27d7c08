#include "common/nmea/nmea_sentence.h"

#include <fmt/format.h>

#include <charconv>
#include <chrono>
#include <cmath>
#include <optional>
#include <vector>

namespace lineloc {
namespace {

constexpr int64_t kNsPerSecond = 1'000'000'000;
constexpr int64_t kNsPerDay = 86'400 * kNsPerSecond;
constexpr size_t kGgaFieldCount = 15;  // "GPGGA" + 14 data fields
constexpr size_t kRmcMinFieldCount = 12;
// GPS began in 1980: RMC's two-digit years 80-99 are 1980-1999, 00-79 are 2000-2079.
constexpr int kFirstTwoDigitYearOf1900s = 80;
// Plausibility limits: beyond them a field is corrupt, not a measurement.
constexpr int kMaxSatellites = 99;
constexpr double kMaxHdop = 99.9;
constexpr double kMaxAbsAltitude_m = 100'000.0;
constexpr double kMaxAbsGeoidSeparation_m = 1'000.0;
constexpr double kMaxSpeed_knots = 10'000.0;

std::vector<std::string_view> splitFields(std::string_view body) {
  std::vector<std::string_view> fields;
  size_t start = 0;
  for (size_t comma = body.find(','); comma != std::string_view::npos;
       comma = body.find(',', start)) {
    fields.push_back(body.substr(start, comma - start));
    start = comma + 1;
  }
  fields.push_back(body.substr(start));
  return fields;
}

std::optional<double> parseDouble(std::string_view text) {
  double value = 0.0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (text.empty() || error != std::errc() || end != text.data() + text.size() ||
      !std::isfinite(value)) {
    return std::nullopt;
  }
  return value;
}

std::optional<int> parseInt(std::string_view text) {
  int value = 0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (text.empty() || error != std::errc() || end != text.data() + text.size()) {
    return std::nullopt;
  }
  return value;
}

bool allDigits(std::string_view text) {
  return text.find_first_not_of("0123456789") == std::string_view::npos;
}

// "hhmmss[.s...]" -> nanoseconds since midnight.
std::optional<int64_t> parseTimeOfDay(std::string_view text) {
  const std::string_view whole = text.substr(0, std::min<size_t>(6, text.size()));
  if (whole.size() != 6 || !allDigits(whole)) {
    return std::nullopt;
  }
  std::string_view fraction;
  if (text.size() > 6) {
    if (text[6] != '.' || text.size() > 16 || !allDigits(text.substr(7))) {
      return std::nullopt;
    }
    fraction = text.substr(7);
  }
  const int hours = *parseInt(whole.substr(0, 2));
  const int minutes = *parseInt(whole.substr(2, 2));
  const int seconds = *parseInt(whole.substr(4, 2));
  if (hours > 23 || minutes > 59 || seconds > 60) {
    return std::nullopt;
  }
  int64_t fraction_ns = 0;
  int64_t scale = kNsPerSecond;
  for (const char digit : fraction) {
    scale /= 10;
    fraction_ns += (digit - '0') * scale;
  }
  return (hours * 3600 + minutes * 60 + seconds) * kNsPerSecond + fraction_ns;
}

// How NMEA writes an angle: "ddmm.mmm,N" for latitude, "dddmm.mmm,E" for longitude.
struct AngleFormat {
  int degree_digits;
  double max_deg;
  char positive;
  char negative;
};
constexpr AngleFormat kLatitude{2, 90.0, 'N', 'S'};
constexpr AngleFormat kLongitude{3, 180.0, 'E', 'W'};

std::optional<double> parseAngle(std::string_view value, std::string_view hemisphere,
                                 const AngleFormat& format) {
  const auto digits = static_cast<size_t>(format.degree_digits);
  if (value.size() < digits + 2 || hemisphere.size() != 1 || !allDigits(value.substr(0, digits))) {
    return std::nullopt;
  }
  const auto degrees = parseInt(value.substr(0, digits));
  const auto minutes = parseDouble(value.substr(digits));
  if (!degrees || !minutes || *minutes < 0.0 || *minutes >= 60.0) {
    return std::nullopt;
  }
  const double angle = *degrees + *minutes / 60.0;
  if (angle > format.max_deg) {
    return std::nullopt;
  }
  if (hemisphere[0] == format.positive) {
    return angle;
  }
  if (hemisphere[0] == format.negative) {
    return -angle;
  }
  return std::nullopt;
}

NmeaParseResult failure(NmeaStatus status, std::string error) {
  NmeaParseResult result;
  result.status = status;
  result.error = std::move(error);
  return result;
}

NmeaParseResult malformed(std::string_view type, std::string_view field) {
  return failure(NmeaStatus::kMalformedField, fmt::format("{}: malformed {} field", type, field));
}

NmeaParseResult parseGga(const std::vector<std::string_view>& f) {
  if (f.size() != kGgaFieldCount) {
    return failure(NmeaStatus::kMalformedField,
                   fmt::format("GGA: {} fields, expected {}", f.size() - 1, kGgaFieldCount - 1));
  }
  GgaSentence gga;
  gga.talker = std::string(f[0].substr(0, 2));
  const auto time = parseTimeOfDay(f[1]);
  const auto quality = parseInt(f[6]);
  if (!time) {
    return malformed("GGA", "time");
  }
  if (!quality || *quality < 0 || *quality > 9) {
    return malformed("GGA", "fix quality");
  }
  gga.time_of_day_ns = *time;
  gga.fix_quality = *quality;
  if (gga.fix_quality == 0) {
    NmeaParseResult result = failure(NmeaStatus::kNoFix, "GGA: fix quality 0 (no fix)");
    result.sentence = gga;
    return result;
  }
  const auto latitude = parseAngle(f[2], f[3], kLatitude);
  const auto longitude = parseAngle(f[4], f[5], kLongitude);
  const auto satellites = parseInt(f[7]);
  const auto hdop = parseDouble(f[8]);
  const auto altitude = parseDouble(f[9]);
  const auto separation = f[11].empty() ? std::optional<double>(0.0) : parseDouble(f[11]);
  if (!latitude)
    return malformed("GGA", "latitude");
  if (!longitude)
    return malformed("GGA", "longitude");
  if (!satellites || *satellites < 0 || *satellites > kMaxSatellites) {
    return malformed("GGA", "satellite count");
  }
  if (!hdop || *hdop < 0.0 || *hdop > kMaxHdop)
    return malformed("GGA", "HDOP");
  if (!altitude || std::abs(*altitude) > kMaxAbsAltitude_m || f[10] != "M") {
    return malformed("GGA", "altitude");
  }
  if (!separation || std::abs(*separation) > kMaxAbsGeoidSeparation_m ||
      (!f[11].empty() && f[12] != "M")) {
    return malformed("GGA", "geoid separation");
  }
  gga.latitude_deg = *latitude;
  gga.longitude_deg = *longitude;
  gga.satellites = *satellites;
  gga.hdop = *hdop;
  gga.altitude_msl_m = *altitude;
  gga.geoid_separation_m = *separation;
  NmeaParseResult result;
  result.status = NmeaStatus::kOk;
  result.sentence = gga;
  return result;
}

std::optional<std::chrono::year_month_day> parseDate(std::string_view text) {
  if (text.size() != 6 || !allDigits(text)) {
    return std::nullopt;
  }
  const int two_digit_year = *parseInt(text.substr(4, 2));
  const int century = two_digit_year < kFirstTwoDigitYearOf1900s ? 2000 : 1900;
  const std::chrono::year_month_day date{std::chrono::year(century + two_digit_year),
                                         std::chrono::month(*parseInt(text.substr(2, 2))),
                                         std::chrono::day(*parseInt(text.substr(0, 2)))};
  return date.ok() ? std::optional(date) : std::nullopt;
}

// An optional field (RMC's speed and course): empty, or a number in [0, max].
bool isEmptyOrWithin(std::string_view field, double max) {
  if (field.empty()) {
    return true;
  }
  const std::optional<double> value = parseDouble(field);
  return value && *value >= 0.0 && *value <= max;
}

std::optional<double> optionalDouble(std::string_view field) {
  return field.empty() ? std::nullopt : parseDouble(field);
}

NmeaParseResult parseRmc(const std::vector<std::string_view>& f) {
  if (f.size() < kRmcMinFieldCount) {
    return failure(NmeaStatus::kMalformedField, fmt::format("RMC: {} fields, expected at least {}",
                                                            f.size() - 1, kRmcMinFieldCount - 1));
  }
  RmcSentence rmc;
  rmc.talker = std::string(f[0].substr(0, 2));
  const auto time = parseTimeOfDay(f[1]);
  const auto date = parseDate(f[9]);
  if (!time)
    return malformed("RMC", "time");
  if (f[2] != "A" && f[2] != "V")
    return malformed("RMC", "status");
  if (!date)
    return malformed("RMC", "date");
  rmc.time_of_day_ns = *time;
  rmc.year = static_cast<int>(date->year());
  rmc.month = static_cast<int>(static_cast<unsigned>(date->month()));
  rmc.day = static_cast<int>(static_cast<unsigned>(date->day()));
  rmc.valid = f[2] == "A";
  if (!rmc.valid) {
    NmeaParseResult result = failure(NmeaStatus::kNoFix, "RMC: status V (no fix)");
    result.sentence = rmc;
    return result;
  }
  const auto latitude = parseAngle(f[3], f[4], kLatitude);
  const auto longitude = parseAngle(f[5], f[6], kLongitude);
  if (!latitude)
    return malformed("RMC", "latitude");
  if (!longitude)
    return malformed("RMC", "longitude");
  if (!isEmptyOrWithin(f[7], kMaxSpeed_knots))
    return malformed("RMC", "speed");
  if (!isEmptyOrWithin(f[8], 360.0))
    return malformed("RMC", "course");
  rmc.latitude_deg = *latitude;
  rmc.longitude_deg = *longitude;
  rmc.speed_knots = optionalDouble(f[7]);
  rmc.course_deg = optionalDouble(f[8]);
  NmeaParseResult result;
  result.status = NmeaStatus::kOk;
  result.sentence = rmc;
  return result;
}

std::string formatTimeOfDay(int64_t time_of_day_ns) {
  const int64_t ms = ((time_of_day_ns % kNsPerDay + kNsPerDay) % kNsPerDay) / 1'000'000;
  const int64_t seconds = ms / 1000;
  return fmt::format("{:02d}{:02d}{:02d}.{:03d}", seconds / 3600, seconds / 60 % 60, seconds % 60,
                     ms % 1000);
}

// Signed degrees -> "ddmm.mmmmmmm,H".
std::string formatAngle(double angle_deg, const AngleFormat& format) {
  const double magnitude = std::abs(angle_deg);
  int degrees = static_cast<int>(magnitude);
  double minutes = std::round((magnitude - degrees) * 60.0 * 1e7) / 1e7;
  if (minutes >= 60.0) {
    degrees += 1;
    minutes -= 60.0;
  }
  return fmt::format("{:0{}d}{:010.7f},{}", degrees, format.degree_digits, minutes,
                     angle_deg < 0.0 ? format.negative : format.positive);
}

std::string withChecksum(const std::string& body) {
  return fmt::format("${}*{:02X}", body, nmeaChecksum(body));
}

}  // namespace

int64_t RmcSentence::utcStamp_ns() const {
  const std::chrono::sys_days date = std::chrono::year_month_day{
      std::chrono::year(year), std::chrono::month(month), std::chrono::day(day)};
  return date.time_since_epoch().count() * kNsPerDay + time_of_day_ns;
}

const char* toString(NmeaStatus status) {
  switch (status) {
    case NmeaStatus::kOk:
      return "ok";
    case NmeaStatus::kNoFix:
      return "no fix";
    case NmeaStatus::kUnsupportedType:
      return "unsupported sentence type";
    case NmeaStatus::kBadFraming:
      return "bad framing";
    case NmeaStatus::kBadChecksum:
      return "bad checksum";
    case NmeaStatus::kMalformedField:
      return "malformed field";
  }
  return "unknown";
}

uint8_t nmeaChecksum(std::string_view body) {
  uint8_t checksum = 0;
  for (const char c : body) {
    checksum ^= static_cast<uint8_t>(c);
  }
  return checksum;
}

NmeaParseResult parseNmeaSentence(std::string_view line) {
  while (!line.empty() && (line.back() == '\n' || line.back() == '\r' || line.back() == ' ')) {
    line.remove_suffix(1);
  }
  while (!line.empty() && line.front() == ' ') {
    line.remove_prefix(1);
  }
  if (line.size() > kMaxNmeaSentenceLength) {
    return failure(NmeaStatus::kBadFraming, fmt::format("sentence of {} bytes exceeds {}",
                                                        line.size(), kMaxNmeaSentenceLength));
  }
  const size_t star = line.rfind('*');
  if (line.empty() || line.front() != '$' || star == std::string_view::npos ||
      star + 3 != line.size()) {
    return failure(NmeaStatus::kBadFraming, "expected '$...*HH'");
  }
  const std::string_view body = line.substr(1, star - 1);
  for (const char c : body) {
    if (c < 0x20 || c > 0x7e || c == '$' || c == '*') {
      return failure(NmeaStatus::kBadFraming, "reserved or non-printable byte in sentence");
    }
  }
  const std::string_view hex = line.substr(star + 1);
  unsigned given = 0;
  const auto [end, error] = std::from_chars(hex.data(), hex.data() + hex.size(), given, 16);
  if (error != std::errc() || end != hex.data() + hex.size()) {
    return failure(NmeaStatus::kBadFraming, fmt::format("checksum '{}' is not hexadecimal", hex));
  }
  if (given != nmeaChecksum(body)) {
    return failure(NmeaStatus::kBadChecksum, fmt::format("checksum {:02X} given, {:02X} computed",
                                                         given, nmeaChecksum(body)));
  }
  const std::vector<std::string_view> fields = splitFields(body);
  const std::string_view address = fields[0];
  if (address.size() != 5) {
    return failure(NmeaStatus::kMalformedField, fmt::format("address '{}'", address));
  }
  if (address.substr(2) == "GGA") {
    return parseGga(fields);
  }
  if (address.substr(2) == "RMC") {
    return parseRmc(fields);
  }
  return failure(NmeaStatus::kUnsupportedType,
                 fmt::format("sentence type '{}' not handled", address));
}

std::string formatGga(const GgaSentence& gga) {
  const bool has_fix = gga.fix_quality != 0;
  const std::string position = has_fix ? formatAngle(gga.latitude_deg, kLatitude) + "," +
                                             formatAngle(gga.longitude_deg, kLongitude)
                                       : ",,,";
  const std::string rest =
      has_fix ? fmt::format("{},{:02d},{:.1f},{:.3f},M,{:.3f},M,,", gga.fix_quality, gga.satellites,
                            gga.hdop, gga.altitude_msl_m, gga.geoid_separation_m)
              : fmt::format("0,{:02d},,,,,,,", gga.satellites);
  return withChecksum(fmt::format("{}GGA,{},{},{}", gga.talker, formatTimeOfDay(gga.time_of_day_ns),
                                  position, rest));
}

std::string formatRmc(const RmcSentence& rmc) {
  const std::string position = rmc.valid ? formatAngle(rmc.latitude_deg, kLatitude) + "," +
                                               formatAngle(rmc.longitude_deg, kLongitude)
                                         : ",,,";
  const auto optional = [](const std::optional<double>& value, int decimals) {
    return value ? fmt::format("{:.{}f}", *value, decimals) : std::string();
  };
  return withChecksum(fmt::format("{}RMC,{},{},{},{},{},{:02d}{:02d}{:02d},,,{}", rmc.talker,
                                  formatTimeOfDay(rmc.time_of_day_ns), rmc.valid ? 'A' : 'V',
                                  position, optional(rmc.speed_knots, 3),
                                  optional(rmc.course_deg, 2), rmc.day, rmc.month, rmc.year % 100,
                                  rmc.valid ? 'D' : 'N'));
}

}  // namespace lineloc
