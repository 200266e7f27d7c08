// The backbones' handovers of their robots' tracking (TrackingHandover,
// tracking_proof.h) on the lineloc_TrackingHandover topic, in the backbones'
// partition: each backbone writes a handover for every frame it answers,
// keyed by robot, each robot's last kept for keep_ns for a backbone that
// starts later (transient-local), and reads the other backbones'. A backbone
// that takes a robot over (backbone_peers.h) offers the robot's newest
// handover, by stamp, read within keep_ns, to its session
// (HandoverChannel, line_set_handler.h), which continues the tracking proof
// from it. Under DDS Security only backbones may write or read handovers; a
// backbone whose identity does not grant them hands nothing over and takes
// nothing over. A malformed handover read is dropped and logged.
#pragma once

#include <cstdint>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>

#include "backbone/service/line_set_handler.h"
#include "backbone/service/tracking_proof.h"
#include "common/dds/dds_entities.h"
#include "common/logging/rate_limited_log.h"

namespace lineloc {

class TrackingHandovers {
 public:
  // `name`: this backbone's (BackbonePeers::name), whose own handovers are
  // not read back.
  TrackingHandovers(const dds::Participant& participant, const std::string& name, int64_t keep_ns);
  ~TrackingHandovers();
  TrackingHandovers(const TrackingHandovers&) = delete;
  TrackingHandovers& operator=(const TrackingHandovers&) = delete;

  void publish(const std::string& robot_id, const TrackingHandover& handover);
  // Keeps `handover` until writeQueued(), in place of one of the same robot
  // queued before: a frame's handover is written after its fix, not before.
  void queue(const std::string& robot_id, const TrackingHandover& handover);
  void writeQueued();

  // The newest handover of `robot_id`, by its stamp, that another backbone
  // wrote and was read within keep_ns.
  std::optional<TrackingHandover> latest(const std::string& robot_id);

  // queue and latest, for a LineSetHandler; this must outlive it.
  HandoverChannel channel();

  // Robots whose newest handover is kept at most: the oldest read is
  // forgotten beyond them.
  static constexpr size_t kMaxRobots = 4096;

 private:
  struct Endpoints;
  // Takes the handovers that have come at `now_ns` (steady clock) into
  // newest_, and forgets those read more than keep_ns before.
  void takeArrived(int64_t now_ns);

  std::string name_;
  int64_t keep_ns_;
  std::unique_ptr<Endpoints> endpoints_;
  RateLimitedLog malformed_log_;
  std::mutex mutex_;
  struct Read {
    TrackingHandover handover;
    int64_t read_ns = 0;  // steady clock
  };
  std::map<std::string, Read> newest_;
  std::mutex queue_mutex_;
  std::map<std::string, TrackingHandover> queued_;
};

}  // namespace lineloc
