// RAII ownership of Cyclone DDS C API handles.
//
// Every handle is deleted exactly once, children before parents. Errors from
// the C API become DdsError carrying dds_strretcode()'s text and what failed.
#pragma once

#include <dds/dds.h>

#include <array>
#include <cstdint>
#include <map>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

namespace lineloc::dds {

class DdsError : public std::runtime_error {
 public:
  DdsError(const std::string& what_failed, dds_return_t code);
};

// Throws DdsError when `code` is negative; returns it otherwise.
dds_return_t check(dds_return_t code, const char* what_failed);

// The GUID of a domain participant: which process (participant) an endpoint
// belongs to.
using ParticipantGuid = std::array<uint8_t, 16>;

enum class EndpointKind { kWriter, kReader };

// Participants of the endpoints matched with `endpoint`: the readers matched
// with a writer, or the writers matched with a reader.
std::vector<ParticipantGuid> matchedParticipants(dds_entity_t endpoint, EndpointKind kind);

// A uniquely owned DDS entity handle.
class Entity {
 public:
  Entity() = default;
  Entity(dds_entity_t handle, const char* what_created);
  ~Entity();
  Entity(Entity&& other) noexcept;
  Entity& operator=(Entity&& other) noexcept;
  Entity(const Entity&) = delete;
  Entity& operator=(const Entity&) = delete;

  dds_entity_t handle() const { return handle_; }

 private:
  dds_entity_t handle_ = 0;
};

// A DDS domain created with an explicit configuration, so tests and programs
// do not depend on the environment. `config_files`: one Cyclone DDS XML file,
// or several separated by commas, each adding to or overriding the ones
// before it; empty: Cyclone's defaults and the CYCLONEDDS_URI environment
// variable apply, as for any DDS program.
//
// Secured: a configuration file holds a Security element (DDS Security's
// plugins, an identity and its permissions; deploy/dds-security.sh). Each
// program logs which it is (logSecurity): unsecured, any participant on the
// domain can read every robot's messages and answer for a backbone.
class Domain {
 public:
  Domain(uint32_t domain_id, const std::string& config_files);
  uint32_t id() const { return id_; }
  bool secured() const { return secured_; }

 private:
  uint32_t id_;
  bool secured_;
  Entity domain_;
};

// Logs whether `domain` is secured: info when it is, a warning when not.
void logSecurity(const Domain& domain);

class Participant {
 public:
  explicit Participant(const Domain& domain);
  dds_entity_t handle() const { return participant_.handle(); }
  ParticipantGuid guid() const;

 private:
  Entity participant_;
};

// QoS of lineloc's data topics: reliable, keep the last `history_depth`
// samples per robot (instance).
class Qos {
 public:
  // Volatile: a reader gets what is written once the writer has matched it.
  explicit Qos(int32_t history_depth);
  // Transient-local with a lifespan: the writer keeps each instance's last
  // `history_depth` samples for `lifespan_ns` after writing them and sends
  // them to a reader it matches in that time, when the reader asks for them
  // with this QoS too. Discovery is not symmetric: a reader may know a writer
  // before the writer knows the reader, and what is written in between would
  // reach nobody.
  static Qos keptForLateReaders(int32_t history_depth, int64_t lifespan_ns);
  // Volatile and best effort: a reader with it matches reliable and
  // best-effort writers alike (ROS 2's sensor drivers publish best effort).
  static Qos anyReliability(int32_t history_depth);
  // A presence: each instance's last sample, transient-local, its writer's
  // liveliness asserted automatically by its participant and lost
  // `lease_ns` after the participant falls silent (killed, paused,
  // disconnected), when the instance stops being alive for its readers
  // (Reader::readInstances).
  static Qos presence(int64_t lease_ns);
  ~Qos();
  Qos(const Qos&) = delete;
  Qos& operator=(const Qos&) = delete;
  const dds_qos_t* get() const { return qos_; }

 private:
  Qos(int32_t history_depth, dds_durability_kind_t durability, int64_t lifespan_ns,
      int64_t liveliness_lease_ns = DDS_INFINITY,
      dds_reliability_kind_t reliability = DDS_RELIABILITY_RELIABLE);

  dds_qos_t* qos_;
};

// The publisher or subscriber of the writers or readers of one partition
// (DDS 1.4 §2.2.3.13): a writer and a reader match only where their
// partitions do, '*' and '?' in a name matching as in fnmatch. For the
// default partition (empty name) no entity is created and endpoints are
// created under the participant itself.
enum class GroupKind { kPublisher, kSubscriber };
Entity createGroup(const Participant& participant, GroupKind kind, const std::string& partition);

// Where the endpoints of `group` (from createGroup) are created.
inline dds_entity_t parentOf(const Entity& group, const Participant& participant) {
  return group.handle() > 0 ? group.handle() : participant.handle();
}

// The partitions of the writer `publication` matched with `reader`; empty
// when it is no longer matched or writes in the default partition.
std::vector<std::string> matchedWriterPartitions(dds_entity_t reader,
                                                 dds_instance_handle_t publication);

// Every partition some writer matched with `reader` writes in, sorted, once each.
std::vector<std::string> partitionsOfMatchedWriters(dds_entity_t reader);

// Message type traits, specialised next to each IDL type (common/messages/topics.h):
// the type's own topic. A second topic of the same type has traits of its own,
// given to Writer and Reader as `Topic`.
template <typename Message>
struct TopicTraits;

// Bytes a sample puts on the wire: its CDR encoding (XCDR1, which Cyclone
// writes for lineloc's final types) plus the 4-byte encapsulation header. The
// RTPS submessage, UDP and IP headers around it are not counted.
uint32_t serializedSizeBytes(const void* sample, const dds_topic_descriptor_t& descriptor);

template <typename Message>
uint32_t serializedSizeBytes(const Message& sample) {
  return serializedSizeBytes(&sample, *TopicTraits<Message>::descriptor());
}

// A writer of Topic's type on Topic's topic, or on `topic_name` (a topic
// named at run time, as a ROS 2 topic is).
template <typename Message, typename Topic = TopicTraits<Message>>
class Writer {
 public:
  Writer(const Participant& participant, const Qos& qos, const std::string& partition = {},
         const std::string& topic_name = Topic::kName)
      : topic_(dds_create_topic(participant.handle(), Topic::descriptor(), topic_name.c_str(),
                                nullptr, nullptr),
               "topic"),
        publisher_(createGroup(participant, GroupKind::kPublisher, partition)),
        writer_(dds_create_writer(parentOf(publisher_, participant), topic_.handle(), qos.get(),
                                  nullptr),
                "writer") {}

  void write(const Message& sample) { check(dds_write(writer_.handle(), &sample), "dds_write"); }

  // Readers currently matched with this writer.
  uint32_t matchedReaders() const {
    dds_publication_matched_status_t status;
    check(dds_get_publication_matched_status(writer_.handle(), &status), "matched status");
    return status.current_count;
  }

  std::vector<ParticipantGuid> matchedReaderParticipants() const {
    return matchedParticipants(writer_.handle(), EndpointKind::kWriter);
  }

 private:
  Entity topic_;
  Entity publisher_;
  Entity writer_;
};

// What DDS tells a reader about a sample besides its data.
struct SampleInfo {
  // When the writer wrote it, on the writer's wall clock (CLOCK_REALTIME ns):
  // comparable with the reader's clock only where the two hosts' clocks are
  // synchronised (one host, or PTP).
  int64_t source_stamp_ns = 0;
  // The writer, for Reader::writerPartitions.
  dds_instance_handle_t publication_handle = 0;
};

template <typename Message, typename Topic = TopicTraits<Message>>
class Reader {
 public:
  Reader(const Participant& participant, const Qos& qos, const std::string& partition = {},
         const std::string& topic_name = Topic::kName)
      : topic_(dds_create_topic(participant.handle(), Topic::descriptor(), topic_name.c_str(),
                                nullptr, nullptr),
               "topic"),
        subscriber_(createGroup(participant, GroupKind::kSubscriber, partition)),
        reader_(dds_create_reader(parentOf(subscriber_, participant), topic_.handle(), qos.get(),
                                  nullptr),
                "reader"),
        waitset_(dds_create_waitset(participant.handle()), "waitset"),
        condition_(dds_create_readcondition(reader_.handle(), DDS_ANY_STATE), "read condition") {
    check(dds_waitset_attach(waitset_.handle(), condition_.handle(), 0), "waitset attach");
  }

  ~Reader() {
    if (waitset_.handle() > 0 && condition_.handle() > 0) {
      dds_waitset_detach(waitset_.handle(), condition_.handle());
    }
  }

  // Blocks until a sample is available or the timeout passes; true when data is there.
  bool waitForData(int64_t timeout_ns) {
    return check(dds_waitset_wait(waitset_.handle(), nullptr, 0, timeout_ns), "waitset wait") > 0;
  }

  // Takes every available sample and calls `handle(const Message&)`, or
  // `handle(const Message&, const SampleInfo&)`, on each valid one (not on
  // disposal notices). Returns the number handled.
  template <typename Handler>
  int takeEach(Handler&& handle) {
    constexpr int kBatch = 16;
    void* samples[kBatch] = {};
    dds_sample_info_t infos[kBatch];
    int handled = 0;
    for (;;) {
      const dds_return_t count =
          check(dds_take(reader_.handle(), samples, infos, kBatch, kBatch), "dds_take");
      for (int i = 0; i < count; ++i) {
        if (!infos[i].valid_data) {
          continue;
        }
        const Message& message = *static_cast<const Message*>(samples[i]);
        if constexpr (std::is_invocable_v<Handler&, const Message&, const SampleInfo&>) {
          handle(message, SampleInfo{infos[i].source_timestamp, infos[i].publication_handle});
        } else {
          handle(message);
        }
        ++handled;
      }
      if (count > 0) {
        dds_return_loan(reader_.handle(), samples, count);
      }
      if (count < kBatch) {
        return handled;
      }
    }
  }

  // Reads, without taking, the samples the reader holds (at most
  // kMaxReadSamples) and calls `handle(const Message&, bool alive)` on each,
  // `alive` when its instance is (some writer of it keeps its liveliness). A
  // sample that only tells of an instance's end carries its key fields alone.
  static constexpr int kMaxReadSamples = 256;
  template <typename Handler>
  void readInstances(Handler&& handle) {
    std::array<void*, kMaxReadSamples> samples{};
    std::array<dds_sample_info_t, kMaxReadSamples> infos;
    const dds_return_t count = check(
        dds_read(reader_.handle(), samples.data(), infos.data(), kMaxReadSamples, kMaxReadSamples),
        "dds_read");
    for (int i = 0; i < count; ++i) {
      handle(*static_cast<const Message*>(samples[i]), infos[i].instance_state == DDS_IST_ALIVE);
    }
    if (count > 0) {
      dds_return_loan(reader_.handle(), samples.data(), count);
    }
  }

  // The reader's handle, for a waitset of several readers.
  dds_entity_t handle() const { return reader_.handle(); }

  // Writers currently matched with this reader.
  uint32_t matchedWriters() const {
    dds_subscription_matched_status_t status;
    check(dds_get_subscription_matched_status(reader_.handle(), &status), "matched status");
    return status.current_count;
  }

  std::vector<ParticipantGuid> matchedWriterParticipants() const {
    return matchedParticipants(reader_.handle(), EndpointKind::kReader);
  }

  // The partitions of the writer of a sample (SampleInfo::publication_handle),
  // asked of DDS once per writer, not per sample: a writer changes its
  // partitions only by being matched anew, under its new ones. Writers no
  // longer matched are forgotten once they outnumber the matched ones.
  const std::vector<std::string>& writerPartitions(dds_instance_handle_t publication) {
    auto known = writer_partitions_.find(publication);
    if (known == writer_partitions_.end()) {
      std::vector<std::string> partitions = matchedWriterPartitions(reader_.handle(), publication);
      if (partitions.empty()) {
        static const std::vector<std::string> kNone;
        return kNone;  // not matched (any more), or the default partition
      }
      if (writer_partitions_.size() >= 2 * size_t{matchedWriters()}) {
        writer_partitions_.clear();
      }
      known = writer_partitions_.emplace(publication, std::move(partitions)).first;
    }
    return known->second;
  }

  // The partitions the matched writers write in (partitionsOfMatchedWriters).
  std::vector<std::string> matchedWritersPartitions() const {
    return partitionsOfMatchedWriters(reader_.handle());
  }

 private:
  Entity topic_;
  Entity subscriber_;
  Entity reader_;
  Entity waitset_;
  Entity condition_;
  std::map<dds_instance_handle_t, std::vector<std::string>> writer_partitions_;
};

}  // namespace lineloc::dds
