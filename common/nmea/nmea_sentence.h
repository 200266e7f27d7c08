// NMEA 0183 GGA and RMC sentences: parsing with checksum verification, and
// formatting with checksums (NMEA 0183 v4.11, §6.2 sentence structure, §6.3
// GGA and RMC). A sentence is "$TTSSS,f1,...,fn*HH": TT the talker (GP, GN,
// ...), SSS the type, HH the XOR of every byte between '$' and '*' in hex.
//
// Latitude and longitude are WGS84 degrees (north and east positive), the
// receiver's own units; time of day is UTC nanoseconds since midnight.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <variant>

namespace lineloc {

// GGA: position fix. A fix quality of 0 means "no fix" and carries no position.
struct GgaSentence {
  std::string talker = "GP";
  int64_t time_of_day_ns = 0;
  double latitude_deg = 0.0;
  double longitude_deg = 0.0;
  int fix_quality = 0;  // 0 none, 1 GPS, 2 DGPS, 4 RTK fixed, 5 RTK float, ...
  int satellites = 0;
  double hdop = 0.0;
  double altitude_msl_m = 0.0;      // antenna height above mean sea level
  double geoid_separation_m = 0.0;  // ellipsoid height = altitude + separation
  double ellipsoidHeight_m() const { return altitude_msl_m + geoid_separation_m; }
};

// RMC: recommended minimum data, the one common sentence that carries the date.
struct RmcSentence {
  std::string talker = "GP";
  int64_t time_of_day_ns = 0;
  bool valid = false;  // status 'A'; 'V' (void) carries no position
  double latitude_deg = 0.0;
  double longitude_deg = 0.0;
  // Over ground, course clockwise from true north; nullopt where the field is
  // empty (a receiver leaves the course out when standing, some the speed too).
  std::optional<double> speed_knots;
  std::optional<double> course_deg;
  int year = 2000;  // four digits; RMC's two-digit yy is 19yy for yy >= 80, else 20yy
  int month = 1;
  int day = 1;
  // UTC nanoseconds since the Unix epoch of this sentence's date and time.
  int64_t utcStamp_ns() const;
};

enum class NmeaStatus {
  kOk,
  kNoFix,            // well-formed GGA with quality 0 or RMC with status 'V'
  kUnsupportedType,  // well-formed, checksum good, but neither GGA nor RMC
  kBadFraming,       // no leading '$', no '*HH', too long, or non-printable bytes
  kBadChecksum,
  kMalformedField,
};

const char* toString(NmeaStatus status);

struct NmeaParseResult {
  NmeaStatus status = NmeaStatus::kBadFraming;
  std::variant<std::monostate, GgaSentence, RmcSentence> sentence;
  std::string error;  // names the offending field when status is not kOk
};

// Longest sentence accepted, '$' to checksum; the standard's limit is 82 with
// CR LF, receivers exceed it with extra precision.
inline constexpr size_t kMaxNmeaSentenceLength = 128;

// XOR of the bytes of `body` (the text between '$' and '*').
uint8_t nmeaChecksum(std::string_view body);

// Parses one sentence; trailing CR/LF and surrounding spaces are ignored.
NmeaParseResult parseNmeaSentence(std::string_view line);

// Formats a sentence with its checksum, without CR LF. Latitude and longitude
// get 7 decimals of arc minutes (0.2 mm), time 3 decimals of seconds.
std::string formatGga(const GgaSentence& gga);
std::string formatRmc(const RmcSentence& rmc);

}  // namespace lineloc
