#include "common/dds/dds_entities.h"

#include <dds/ddsi/ddsi_cdrstream.h>
#include <dds/ddsi/q_protocol.h>
#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <utility>

namespace lineloc::dds {

DdsError::DdsError(const std::string& what_failed, dds_return_t code)
    : std::runtime_error(fmt::format("DDS {} failed: {}", what_failed, dds_strretcode(code))) {}

uint32_t serializedSizeBytes(const void* sample, const dds_topic_descriptor_t& descriptor) {
  constexpr uint32_t kEncapsulationHeaderBytes = 4;
  dds_ostream_t stream;
  dds_ostream_init(&stream, 0, CDR_ENC_VERSION_1);
  dds_stream_write(&stream, static_cast<const char*>(sample), descriptor.m_ops);
  const uint32_t payload_bytes = stream.m_index;
  dds_ostream_fini(&stream);
  return kEncapsulationHeaderBytes + payload_bytes;
}

dds_return_t check(dds_return_t code, const char* what_failed) {
  if (code < 0) {
    throw DdsError(what_failed, code);
  }
  return code;
}

namespace {

ParticipantGuid toParticipantGuid(const dds_guid_t& guid) {
  ParticipantGuid result;
  std::copy(std::begin(guid.v), std::end(guid.v), result.begin());
  return result;
}

// The instance handles of the endpoints matched with `endpoint`.
std::vector<dds_instance_handle_t> matchedHandles(dds_entity_t endpoint, EndpointKind kind) {
  const bool is_writer = kind == EndpointKind::kWriter;
  const auto matched = [&](dds_instance_handle_t* handles, size_t capacity) {
    return check(is_writer ? dds_get_matched_subscriptions(endpoint, handles, capacity)
                           : dds_get_matched_publications(endpoint, handles, capacity),
                 "matched endpoints");
  };
  std::vector<dds_instance_handle_t> handles(static_cast<size_t>(matched(nullptr, 0)));
  handles.resize(
      std::min(handles.size(), static_cast<size_t>(matched(handles.data(), handles.size()))));
  return handles;
}

}  // namespace

std::vector<ParticipantGuid> matchedParticipants(dds_entity_t endpoint, EndpointKind kind) {
  const bool is_writer = kind == EndpointKind::kWriter;
  std::vector<ParticipantGuid> participants;
  for (const dds_instance_handle_t handle : matchedHandles(endpoint, kind)) {
    dds_builtintopic_endpoint_t* matched_endpoint =
        is_writer ? dds_get_matched_subscription_data(endpoint, handle)
                  : dds_get_matched_publication_data(endpoint, handle);
    if (matched_endpoint == nullptr) {
      continue;  // unmatched since it was listed
    }
    participants.push_back(toParticipantGuid(matched_endpoint->participant_key));
    dds_builtintopic_free_endpoint(matched_endpoint);
  }
  return participants;
}

std::vector<std::string> matchedWriterPartitions(dds_entity_t reader,
                                                 dds_instance_handle_t publication) {
  dds_builtintopic_endpoint_t* writer = dds_get_matched_publication_data(reader, publication);
  if (writer == nullptr) {
    return {};
  }
  uint32_t count = 0;
  char** names = nullptr;
  std::vector<std::string> partitions;
  if (dds_qget_partition(writer->qos, &count, &names)) {
    for (uint32_t i = 0; i < count; ++i) {
      partitions.emplace_back(names[i]);
      dds_free(names[i]);
    }
    dds_free(names);
  }
  dds_builtintopic_free_endpoint(writer);
  return partitions;
}

std::vector<std::string> partitionsOfMatchedWriters(dds_entity_t reader) {
  std::vector<std::string> partitions;
  for (const dds_instance_handle_t handle : matchedHandles(reader, EndpointKind::kReader)) {
    const std::vector<std::string> of_writer = matchedWriterPartitions(reader, handle);
    partitions.insert(partitions.end(), of_writer.begin(), of_writer.end());
  }
  std::sort(partitions.begin(), partitions.end());
  partitions.erase(std::unique(partitions.begin(), partitions.end()), partitions.end());
  return partitions;
}

Entity::Entity(dds_entity_t handle, const char* what_created) : handle_(handle) {
  check(handle, what_created);
}

Entity::~Entity() {
  if (handle_ > 0) {
    dds_delete(handle_);
  }
}

Entity::Entity(Entity&& other) noexcept : handle_(std::exchange(other.handle_, 0)) {}

Entity& Entity::operator=(Entity&& other) noexcept {
  if (this != &other) {
    if (handle_ > 0) {
      dds_delete(handle_);
    }
    handle_ = std::exchange(other.handle_, 0);
  }
  return *this;
}

namespace {

// "file://a,file://b" for "a,b": Cyclone reads the files of such a list in
// turn, each adding to or overriding the ones before.
std::string configUri(const std::string& config_files) {
  std::string uri;
  std::stringstream files(config_files);
  for (std::string file; std::getline(files, file, ',');) {
    if (!std::filesystem::is_regular_file(file)) {
      throw std::runtime_error(fmt::format("DDS config file '{}' does not exist", file));
    }
    uri += (uri.empty() ? "file://" : ",file://") + std::filesystem::absolute(file).string();
  }
  return uri;
}

Entity createDomain(uint32_t domain_id, const std::string& config_files) {
  if (config_files.empty()) {
    return {};
  }
  const dds_entity_t domain = dds_create_domain(domain_id, configUri(config_files).c_str());
  if (domain == DDS_RETCODE_PRECONDITION_NOT_MET) {
    // Already created in this process (by another Domain object): share it.
    return {};
  }
  return Entity(domain, "create domain");
}

// True when one of `config_files` (as for Domain) has a Security element.
bool namesSecurity(const std::string& config_files) {
  std::stringstream files(config_files);
  for (std::string file; std::getline(files, file, ',');) {
    std::ifstream stream(file);
    const std::string text{std::istreambuf_iterator<char>(stream),
                           std::istreambuf_iterator<char>()};
    if (text.find("<Security>") != std::string::npos) {
      return true;
    }
  }
  return false;
}

}  // namespace

Domain::Domain(uint32_t domain_id, const std::string& config_files)
    : id_(domain_id),
      secured_(namesSecurity(config_files)),
      domain_(createDomain(domain_id, config_files)) {}

void logSecurity(const Domain& domain) {
  if (domain.secured()) {
    spdlog::info("DDS Security on: authenticated participants only, encrypted, as permitted");
  } else {
    spdlog::warn(
        "DDS Security is off: any participant on DDS domain {} can read this program's messages "
        "and write its peers'; for development only (secure with deploy/dds-security.sh)",
        domain.id());
  }
}

Participant::Participant(const Domain& domain)
    : participant_(dds_create_participant(domain.id(), nullptr, nullptr), "create participant") {}

Entity createGroup(const Participant& participant, GroupKind kind, const std::string& partition) {
  if (partition.empty()) {
    return {};
  }
  dds_qos_t* qos = dds_create_qos();
  const char* names[] = {partition.c_str()};
  dds_qset_partition(qos, 1, names);
  const dds_entity_t group = kind == GroupKind::kPublisher
                                 ? dds_create_publisher(participant.handle(), qos, nullptr)
                                 : dds_create_subscriber(participant.handle(), qos, nullptr);
  dds_delete_qos(qos);
  return Entity(group, kind == GroupKind::kPublisher ? "create publisher" : "create subscriber");
}

ParticipantGuid Participant::guid() const {
  dds_guid_t guid;
  check(dds_get_guid(participant_.handle(), &guid), "participant guid");
  return toParticipantGuid(guid);
}

Qos::Qos(int32_t history_depth) : Qos(history_depth, DDS_DURABILITY_VOLATILE, DDS_INFINITY) {}

Qos Qos::keptForLateReaders(int32_t history_depth, int64_t lifespan_ns) {
  return Qos(history_depth, DDS_DURABILITY_TRANSIENT_LOCAL, lifespan_ns);
}

Qos Qos::anyReliability(int32_t history_depth) {
  return Qos(history_depth, DDS_DURABILITY_VOLATILE, DDS_INFINITY, DDS_INFINITY,
             DDS_RELIABILITY_BEST_EFFORT);
}

Qos Qos::presence(int64_t lease_ns) {
  return Qos(1, DDS_DURABILITY_TRANSIENT_LOCAL, DDS_INFINITY, lease_ns);
}

Qos::Qos(int32_t history_depth, dds_durability_kind_t durability, int64_t lifespan_ns,
         int64_t liveliness_lease_ns, dds_reliability_kind_t reliability)
    : qos_(dds_create_qos()) {
  dds_qset_reliability(qos_, reliability, DDS_MSECS(100));
  dds_qset_durability(qos_, durability);
  dds_qset_history(qos_, DDS_HISTORY_KEEP_LAST, history_depth);
  // What a transient-local writer keeps for late readers (Cyclone's default: 1 sample).
  dds_qset_durability_service(qos_, 0, DDS_HISTORY_KEEP_LAST, history_depth, DDS_LENGTH_UNLIMITED,
                              DDS_LENGTH_UNLIMITED, DDS_LENGTH_UNLIMITED);
  dds_qset_lifespan(qos_, lifespan_ns);
  dds_qset_liveliness(qos_, DDS_LIVELINESS_AUTOMATIC, liveliness_lease_ns);
}

Qos::~Qos() {
  dds_delete_qos(qos_);
}

}  // namespace lineloc::dds
