// Turns one received LineSet into its PoseFix: validate, read the model lines
// near the predicted pose, answer. Until matching exists the answer is honest:
// the predicted pose and covariance, the number of model lines found, and the
// status FIX_NO_MATCH_COMPUTED (FIX_NO_MAP_LINES when none are near).
// Malformed input is dropped and counted; a database failure is answered
// with FIX_INTERNAL_ERROR and counted, and serving goes on.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "backbone/map/model_map.h"
#include "common/messages/message_validator.h"
#include "common/messages/messages.h"

namespace lineloc {

struct BackboneCounters {
  uint64_t received = 0;
  uint64_t answered = 0;
  uint64_t dropped_invalid = 0;
  uint64_t map_errors = 0;
  std::string last_drop_reason;
};

class LineSetHandler {
 public:
  LineSetHandler(ModelMap& map, const MessageLimits& limits, double query_radius_m);

  // The fix to publish, or nullopt when the message was dropped.
  std::optional<PoseFixData> handle(const lineloc_msg_LineSet& message);

  const BackboneCounters& counters() const { return counters_; }

 private:
  ModelMap& map_;
  MessageLimits limits_;
  double query_radius_m_;
  BackboneCounters counters_;
};

}  // namespace lineloc
