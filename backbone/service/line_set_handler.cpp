#include "backbone/service/line_set_handler.h"

#include <spdlog/spdlog.h>

#include "common/time/clock.h"

namespace lineloc {

LineSetHandler::LineSetHandler(ModelMap& map, const MessageLimits& limits, double query_radius_m)
    : map_(map), limits_(limits), query_radius_m_(query_radius_m) {}

std::optional<PoseFixData> LineSetHandler::handle(const lineloc_msg_LineSet& message) {
  const int64_t start_ns = steadyClockNs();
  ++counters_.received;
  if (const std::optional<std::string> error = findLineSetError(message, limits_)) {
    ++counters_.dropped_invalid;
    counters_.last_drop_reason = *error;
    spdlog::warn("dropped LineSet #{}: {}", message.sequence_number, *error);
    return std::nullopt;
  }
  const LineSetData line_set = fromMessage(message);
  PoseFixData fix;
  fix.robot_id = line_set.robot_id;
  fix.sequence_number = line_set.sequence_number;
  fix.stamp_ns = line_set.stamp_ns;
  fix.T_world_camera = line_set.predicted_T_world_camera;
  try {
    const auto lines =
        map_.linesNear(line_set.predicted_T_world_camera.pose.translation(), query_radius_m_);
    fix.model_lines = static_cast<uint32_t>(lines.size());
    fix.status = lines.empty() ? lineloc_msg_FIX_NO_MAP_LINES : lineloc_msg_FIX_NO_MATCH_COMPUTED;
  } catch (const std::exception& error) {
    ++counters_.map_errors;
    spdlog::error("map query for {} #{} failed: {}", fix.robot_id, fix.sequence_number,
                  error.what());
    fix.status = lineloc_msg_FIX_INTERNAL_ERROR;
  }
  fix.timings.map = steadyClockNs() - start_ns;
  fix.timings.total = fix.timings.map;
  ++counters_.answered;
  return fix;
}

}  // namespace lineloc
