#include "backbone/service/tracking_handovers.h"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <cstdio>

#include "common/messages/message_validator.h"
#include "common/messages/topics.h"
#include "common/time/clock.h"

namespace lineloc {
namespace {

lineloc_msg_TrackingHandover toMessage(const std::string& robot_id, const std::string& backbone,
                                       const TrackingHandover& handover) {
  lineloc_msg_TrackingHandover message{};
  std::snprintf(message.robot_id, sizeof(message.robot_id), "%s", robot_id.c_str());
  std::snprintf(message.backbone, sizeof(message.backbone), "%s", backbone.c_str());
  message.stamp_ns = handover.stamp_ns;
  message.tracking = handover.tracking;
  message.agreeing_proofs = static_cast<uint32_t>(std::max(handover.agreeing_proofs, 0));
  message.proof_due_in_m = handover.proof_due_in_m;
  message.rival_position_m = handover.rival.position_m;
  message.rival_rotation_rad = handover.rival.rotation_rad;
  message.looked_around = handover.looked_around;
  const std::vector<Eigen::Isometry3d>& hypotheses = handover.hypotheses.T_prediction_camera;
  message.hypothesis_count =
      static_cast<uint32_t>(std::min<size_t>(hypotheses.size(), lineloc_msg_MAX_HANDED_HYPOTHESES));
  for (uint32_t i = 0; i < message.hypothesis_count; ++i) {
    message.hypotheses_T_prediction_camera[i] = lineloc::toMessage(hypotheses[i]);
  }
  message.hypotheses_stamp_ns = handover.hypotheses.stamp_ns;
  return message;
}

TrackingHandover fromMessage(const lineloc_msg_TrackingHandover& message) {
  TrackingHandover handover{.stamp_ns = message.stamp_ns,
                            .tracking = message.tracking,
                            .agreeing_proofs = static_cast<int>(message.agreeing_proofs),
                            .proof_due_in_m = message.proof_due_in_m,
                            .rival = {message.rival_position_m, message.rival_rotation_rad},
                            .looked_around = message.looked_around,
                            .hypotheses = {message.hypotheses_stamp_ns, {}}};
  for (uint32_t i = 0; i < message.hypothesis_count; ++i) {
    handover.hypotheses.T_prediction_camera.push_back(
        lineloc::fromMessage(message.hypotheses_T_prediction_camera[i]));
  }
  return handover;
}

}  // namespace

struct TrackingHandovers::Endpoints {
  Endpoints(const dds::Participant& participant, int64_t keep_ns)
      : qos(dds::Qos::keptForLateReaders(1, keep_ns)),
        writer(participant, qos, dds::kBackbonePartition),
        reader(participant, qos, dds::kBackbonePartition) {}

  dds::Qos qos;
  dds::Writer<lineloc_msg_TrackingHandover> writer;
  dds::Reader<lineloc_msg_TrackingHandover> reader;
};

TrackingHandovers::TrackingHandovers(const dds::Participant& participant, const std::string& name,
                                     int64_t keep_ns)
    : name_(name), keep_ns_(keep_ns), malformed_log_("malformed tracking handovers", 1, 10.0) {
  try {
    endpoints_ = std::make_unique<Endpoints>(participant, keep_ns);
  } catch (const dds::DdsError& error) {
    spdlog::warn(
        "this backbone cannot hand its robots' tracking over to other backbones ({}): a robot "
        "taken over is proven again; issue its identity again (deploy/dds-security.sh)",
        error.what());
  }
}

TrackingHandovers::~TrackingHandovers() = default;

void TrackingHandovers::publish(const std::string& robot_id, const TrackingHandover& handover) {
  if (endpoints_) {
    endpoints_->writer.write(toMessage(robot_id, name_, handover));
  }
}

void TrackingHandovers::queue(const std::string& robot_id, const TrackingHandover& handover) {
  const std::lock_guard<std::mutex> lock(queue_mutex_);
  queued_[robot_id] = handover;
}

void TrackingHandovers::writeQueued() {
  std::map<std::string, TrackingHandover> queued;
  {
    const std::lock_guard<std::mutex> lock(queue_mutex_);
    queued.swap(queued_);
  }
  for (const auto& [robot_id, handover] : queued) {
    publish(robot_id, handover);
  }
}

void TrackingHandovers::takeArrived(int64_t now_ns) {
  endpoints_->reader.takeEach([&](const lineloc_msg_TrackingHandover& message) {
    if (const std::optional<std::string> error = findTrackingHandoverError(message)) {
      malformed_log_.log("tracking handover dropped: " + *error);
      return;
    }
    if (message.backbone == name_) {
      return;
    }
    Read& read = newest_[message.robot_id];
    if (read.read_ns == 0 || message.stamp_ns >= read.handover.stamp_ns) {
      read.handover = fromMessage(message);
    }
    read.read_ns = now_ns;
  });
  std::erase_if(newest_, [&](const auto& read) { return now_ns - read.second.read_ns > keep_ns_; });
  while (newest_.size() > kMaxRobots) {
    newest_.erase(std::min_element(
        newest_.begin(), newest_.end(),
        [](const auto& a, const auto& b) { return a.second.read_ns < b.second.read_ns; }));
  }
}

std::optional<TrackingHandover> TrackingHandovers::latest(const std::string& robot_id) {
  if (!endpoints_) {
    return std::nullopt;
  }
  const std::lock_guard<std::mutex> lock(mutex_);
  takeArrived(steadyClockNs());
  const auto found = newest_.find(robot_id);
  return found != newest_.end() ? std::optional(found->second.handover) : std::nullopt;
}

HandoverChannel TrackingHandovers::channel() {
  return {[this](const std::string& robot_id, const TrackingHandover& handover) {
            queue(robot_id, handover);
          },
          [this](const std::string& robot_id) { return latest(robot_id); }};
}

}  // namespace lineloc
