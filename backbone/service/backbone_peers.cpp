#include "backbone/service/backbone_peers.h"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <cstdio>
#include <stdexcept>

#include "backbone/service/robot_assignment.h"
#include "common/messages/message_validator.h"
#include "common/messages/topics.h"

namespace lineloc {

struct BackbonePeers::Endpoints {
  Endpoints(const dds::Participant& participant, int64_t lease_ns)
      : qos(dds::Qos::presence(lease_ns)),
        writer(participant, qos, dds::kBackbonePartition),
        reader(participant, qos, dds::kBackbonePartition) {}

  dds::Qos qos;
  dds::Writer<lineloc_msg_BackbonePresence> writer;
  dds::Reader<lineloc_msg_BackbonePresence> reader;
};

BackbonePeers::BackbonePeers(const dds::Participant& participant, const std::string& name,
                             int64_t lease_ns)
    : name_(name), alive_({name}) {
  if (!isValidBackboneName(name)) {
    throw std::invalid_argument("backbone name '" + name +
                                "' must match [A-Za-z0-9][A-Za-z0-9_.-]* (at most 64 characters)");
  }
  if (!(lease_ns > 0)) {
    throw std::invalid_argument("the backbones' liveliness lease must be positive");
  }
  try {
    endpoints_ = std::make_unique<Endpoints>(participant, lease_ns);
  } catch (const dds::DdsError& error) {
    spdlog::warn(
        "backbone '{}' cannot announce itself to other backbones ({}): it serves every robot; "
        "issue its identity again (deploy/dds-security.sh) to share them",
        name_, error.what());
    return;
  }
  lineloc_msg_BackbonePresence presence{};
  std::snprintf(presence.name, sizeof(presence.name), "%s", name_.c_str());
  endpoints_->writer.write(presence);
}

BackbonePeers::~BackbonePeers() = default;

std::vector<std::string> BackbonePeers::refresh() {
  std::vector<std::string> names = {name_};
  if (endpoints_) {
    endpoints_->reader.readInstances([&](const lineloc_msg_BackbonePresence& presence, bool alive) {
      const std::string name(presence.name);
      if (alive && !name.empty() && std::find(names.begin(), names.end(), name) == names.end()) {
        names.push_back(name);
      }
    });
  }
  std::sort(names.begin(), names.end());
  const std::lock_guard<std::mutex> lock(mutex_);
  alive_ = names;
  return names;
}

bool BackbonePeers::serves(const std::string& robot_id) const {
  const std::lock_guard<std::mutex> lock(mutex_);
  return servingBackbone(robot_id, alive_) == name_;
}

}  // namespace lineloc
