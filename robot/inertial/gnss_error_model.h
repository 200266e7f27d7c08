// A GNSS fix's uncertainty from what the receiver reports with it: its fix
// quality (NMEA GGA field 6, or gpsd's status) and its horizontal dilution
// of precision. A position's error is the satellites' geometry, the dilution
// of precision, times the ranging error of the fix's kind (Misra & Enge,
// "Global Positioning System", ch. 6): per horizontal axis sigma_h = HDOP *
// sigma_q, with sigma_q this model's value for the quality, and vertically
// sigma_v = vertical_ratio * sigma_h (GGA reports no VDOP; with the horizon
// masked by buildings it is about twice HDOP).
//
// The defaults are a receiver in a street, where multipath, not the
// satellites' geometry, dominates: a DGPS fix at HDOP 0.9 is good to about
// 5 m per axis.
#pragma once

#include <optional>

namespace lineloc {

struct GnssErrorModel {
  // sigma_q per horizontal axis at HDOP 1 (m), by fix quality.
  double gps_sigma_m = 8.0;         // 1: autonomous
  double dgps_sigma_m = 5.5;        // 2: differential (also SBAS)
  double rtk_fixed_sigma_m = 0.05;  // 4: RTK, ambiguities fixed
  double rtk_float_sigma_m = 0.5;   // 5: RTK, float
  double vertical_ratio = 2.0;
};

// The GGA fix qualities this model knows; of the others, 0 is no fix, and 3
// (PPS), 6 (dead reckoning), 7 (manual) and 8 (simulation) say nothing of
// the error.
enum class GnssFixQuality { kNone = 0, kGps = 1, kDgps = 2, kRtkFixed = 4, kRtkFloat = 5 };

struct GnssSigmas {
  double horizontal_m = 0.0;  // per axis
  double vertical_m = 0.0;
};

// The sigmas of a fix of GGA quality `quality` at `hdop`; nullopt, the
// navigator's configured sigmas to be used, for a quality the model does not
// know or an HDOP that is not positive and finite (the receiver did not say).
std::optional<GnssSigmas> gnssSigmas(int quality, double hdop, const GnssErrorModel& model);

// Throws std::invalid_argument naming the first value that is not positive.
void validate(const GnssErrorModel& model);

}  // namespace lineloc
