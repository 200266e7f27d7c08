#include "common/dds/dds_entities.h"

#include <dds/ddsi/ddsi_cdrstream.h>
#include <dds/ddsi/q_protocol.h>
#include <fmt/format.h>

#include <filesystem>
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

Entity createDomain(uint32_t domain_id, const std::string& config_file) {
  if (config_file.empty()) {
    return {};
  }
  if (!std::filesystem::is_regular_file(config_file)) {
    throw std::runtime_error(fmt::format("DDS config file '{}' does not exist", config_file));
  }
  const std::string uri = "file://" + std::filesystem::absolute(config_file).string();
  const dds_entity_t domain = dds_create_domain(domain_id, uri.c_str());
  if (domain == DDS_RETCODE_PRECONDITION_NOT_MET) {
    // Already created in this process (by another Domain object): share it.
    return {};
  }
  return Entity(domain, "create domain");
}

}  // namespace

Domain::Domain(uint32_t domain_id, const std::string& config_file)
    : id_(domain_id), domain_(createDomain(domain_id, config_file)) {}

Participant::Participant(const Domain& domain)
    : participant_(dds_create_participant(domain.id(), nullptr, nullptr), "create participant") {}

Qos::Qos(int32_t history_depth) : qos_(dds_create_qos()) {
  dds_qset_reliability(qos_, DDS_RELIABILITY_RELIABLE, DDS_MSECS(100));
  dds_qset_durability(qos_, DDS_DURABILITY_VOLATILE);
  dds_qset_history(qos_, DDS_HISTORY_KEEP_LAST, history_depth);
}

Qos::~Qos() {
  dds_delete_qos(qos_);
}

}  // namespace lineloc::dds
