// A topic's samples as the bytes DDS carries them (the CDR encapsulation
// header and the encoded sample), read and written without decoding: what a
// test hands to an independent implementation of the encoding, and takes
// back from it.
#pragma once

#include <dds/dds.h>

#include <cstdint>
#include <string>
#include <vector>

#include "common/dds/dds_entities.h"

namespace lineloc::test {

class SerializedReader {
 public:
  SerializedReader(const dds::Participant& participant, const dds_topic_descriptor_t& type,
                   const std::string& topic);
  // The samples that arrive within `timeout_ns`, each as its bytes.
  std::vector<std::vector<uint8_t>> take(int64_t timeout_ns);

 private:
  dds::Entity topic_;
  dds::Entity reader_;
};

class SerializedWriter {
 public:
  SerializedWriter(const dds::Participant& participant, const dds_topic_descriptor_t& type,
                   const std::string& topic);
  // Writes one sample given as its bytes (little-endian plain CDR, as ROS 2
  // writes), read by Cyclone DDS's CDR stream as a reader reads what arrives.
  // Throws std::runtime_error when they are not a sample of the type.
  void write(const std::vector<uint8_t>& bytes);
  uint32_t matchedReaders() const;

 private:
  const dds_topic_descriptor_t& type_;
  dds::Entity topic_;
  dds::Entity writer_;
};

}  // namespace lineloc::test
