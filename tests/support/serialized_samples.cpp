#include "tests/support/serialized_samples.h"

#include <dds/ddsi/ddsi_cdrstream.h>
#include <dds/ddsi/ddsi_serdata.h>
#include <dds/ddsi/q_protocol.h>

#include <chrono>
#include <stdexcept>
#include <thread>

namespace lineloc::test {
namespace {

dds_entity_t createTopic(const dds::Participant& participant, const dds_topic_descriptor_t& type,
                         const std::string& topic) {
  return dds_create_topic(participant.handle(), &type, topic.c_str(), nullptr, nullptr);
}

}  // namespace

SerializedReader::SerializedReader(const dds::Participant& participant,
                                   const dds_topic_descriptor_t& type, const std::string& topic)
    : topic_(createTopic(participant, type, topic), "topic"),
      reader_(dds_create_reader(participant.handle(), topic_.handle(), dds::Qos(64).get(), nullptr),
              "reader") {}

std::vector<std::vector<uint8_t>> SerializedReader::take(int64_t timeout_ns) {
  std::vector<std::vector<uint8_t>> samples;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::nanoseconds(timeout_ns);
  while (samples.empty() && std::chrono::steady_clock::now() < deadline) {
    ddsi_serdata* data[16] = {};
    dds_sample_info_t infos[16];
    const dds_return_t count = dds_takecdr(reader_.handle(), data, 16, infos, DDS_ANY_STATE);
    for (dds_return_t i = 0; i < count; ++i) {
      if (infos[i].valid_data) {
        std::vector<uint8_t> bytes(ddsi_serdata_size(data[i]));
        ddsi_serdata_to_ser(data[i], 0, bytes.size(), bytes.data());
        samples.push_back(std::move(bytes));
      }
      ddsi_serdata_unref(data[i]);
    }
    if (samples.empty()) {
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
  }
  return samples;
}

SerializedWriter::SerializedWriter(const dds::Participant& participant,
                                   const dds_topic_descriptor_t& type, const std::string& topic)
    : type_(type),
      topic_(createTopic(participant, type, topic), "topic"),
      writer_(dds_create_writer(participant.handle(), topic_.handle(), dds::Qos(64).get(), nullptr),
              "writer") {}

void SerializedWriter::write(const std::vector<uint8_t>& bytes) {
  // CDR_LE: the 2-byte encapsulation identifier 0x0001, 2 bytes of options.
  constexpr size_t kHeaderBytes = 4;
  if (bytes.size() < kHeaderBytes || bytes[0] != 0x00 || bytes[1] != 0x01) {
    throw std::runtime_error("not little-endian plain CDR (encapsulation 0x0001)");
  }
  std::vector<char> body(bytes.begin() + kHeaderBytes, bytes.end());
  uint32_t size = static_cast<uint32_t>(body.size());
  uint32_t offset = 0;
  // As a reader does with what arrives: checked against the type, then read.
  if (dds_stream_normalize_data(body.data(), &offset, size, false, CDR_ENC_VERSION_1,
                                type_.m_ops) == nullptr) {
    throw std::runtime_error("the bytes are no sample of the topic's type");
  }
  std::vector<char> sample(type_.m_size, 0);
  dds_istream_t stream;
  dds_istream_init(&stream, size, body.data(), CDR_ENC_VERSION_1);
  dds_stream_read(&stream, sample.data(), type_.m_ops);
  dds_istream_fini(&stream);
  const dds_return_t written = dds_write(writer_.handle(), sample.data());
  dds_stream_free_sample(sample.data(), type_.m_ops);
  dds::check(written, "dds_write");
}

uint32_t SerializedWriter::matchedReaders() const {
  dds_publication_matched_status_t status;
  dds::check(dds_get_publication_matched_status(writer_.handle(), &status), "matched status");
  return status.current_count;
}

}  // namespace lineloc::test
