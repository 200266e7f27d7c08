#include "robot/inertial/navigator_measurements.h"

#include <stdexcept>

namespace lineloc {

int64_t& counterOf(MeasurementCounters& counters, MeasurementOutcome outcome) {
  switch (outcome) {
    case MeasurementOutcome::kAccepted:
      return counters.accepted;
    case MeasurementOutcome::kGated:
      return counters.gated;
    case MeasurementOutcome::kDegenerate:
      return counters.degenerate;
    case MeasurementOutcome::kSkipped:
      return counters.skipped;
    case MeasurementOutcome::kTooLate:
      return counters.too_late;
    case MeasurementOutcome::kInvalid:
      return counters.invalid;
    case MeasurementOutcome::kPending:
      break;
  }
  throw std::logic_error("a pending measurement has no counter");
}

}  // namespace lineloc
