// The backbones sharing a DDS domain's robots, as each of them sees them:
// every backbone writes its presence (its name) on the lineloc_Backbone
// topic, with a liveliness lease (dds::Qos::presence), and reads everyone's.
// A backbone killed, paused or cut off stops being alive for the others one
// lease after it fell silent; they then serve its robots
// (robot_assignment.h), and it takes its share back once it is heard again.
// A backbone alone, or one whose presence was refused (a domain secured
// without it), serves every robot.
#pragma once

#include <cstdint>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "common/dds/dds_entities.h"

namespace lineloc {

class BackbonePeers {
 public:
  // Announces `name` ([A-Za-z0-9][A-Za-z0-9_.-]*, at most 64 characters) on
  // `participant`'s domain with liveliness lease `lease_ns`; throws
  // std::invalid_argument on a name that is not.
  BackbonePeers(const dds::Participant& participant, const std::string& name, int64_t lease_ns);
  ~BackbonePeers();
  BackbonePeers(const BackbonePeers&) = delete;
  BackbonePeers& operator=(const BackbonePeers&) = delete;

  const std::string& name() const { return name_; }

  // Looks which backbones are alive now and returns them, this one among
  // them, sorted; serves() answers among them from then on.
  std::vector<std::string> refresh();

  // Whether this backbone serves `robot_id` among the backbones alive at the
  // last refresh(). Safe to call beside refresh().
  bool serves(const std::string& robot_id) const;

 private:
  struct Endpoints;
  std::string name_;
  std::unique_ptr<Endpoints> endpoints_;
  mutable std::mutex mutex_;
  std::vector<std::string> alive_;
};

}  // namespace lineloc
