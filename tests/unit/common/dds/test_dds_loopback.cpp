// Real Cyclone DDS participants on loopback, configured by deploy/cyclonedds.xml.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <thread>

#include "common/messages/messages.h"
#include "common/messages/topics.h"
#include "common/time/clock.h"
#include "tests/support/test_dds.h"
#include "tests/support/wait_for.h"

namespace lineloc {
namespace {

using test::waitFor;

namespace fs = std::filesystem;

TEST(DdsLoopback, MatchedEndpointsNameTheirParticipants) {
  dds::Domain domain(test::testDomainId(), test::testDdsConfig());
  dds::Participant robot(domain);
  dds::Participant backbone(domain);
  dds::Participant listener(domain);
  dds::Writer<lineloc_msg_LineSet> line_sets(robot, dds::Qos(8));
  dds::Reader<lineloc_msg_PoseFix> fixes(robot, dds::Qos(8));
  dds::Reader<lineloc_msg_LineSet> backbone_line_sets(backbone, dds::Qos(8));
  dds::Writer<lineloc_msg_PoseFix> backbone_fixes(backbone, dds::Qos(8));
  dds::Reader<lineloc_msg_LineSet> listener_line_sets(listener, dds::Qos(8));
  ASSERT_TRUE(
      waitFor([&] { return line_sets.matchedReaders() == 2 && fixes.matchedWriters() == 1; }));
  std::vector<dds::ParticipantGuid> readers = line_sets.matchedReaderParticipants();
  std::sort(readers.begin(), readers.end());
  std::vector<dds::ParticipantGuid> expected = {backbone.guid(), listener.guid()};
  std::sort(expected.begin(), expected.end());
  EXPECT_EQ(readers, expected);
  EXPECT_EQ(fixes.matchedWriterParticipants(), std::vector<dds::ParticipantGuid>{backbone.guid()});
  EXPECT_NE(robot.guid(), backbone.guid());
}

TEST(DdsLoopback, PartitionsMatchByPatternAndTheReaderSeesTheWritersPartition) {
  dds::Domain domain(test::testDomainId(), test::testDdsConfig());
  dds::Participant robot(domain);
  dds::Participant other_robot(domain);
  dds::Participant backbone(domain);
  dds::Writer<lineloc_msg_LineSet> own(robot, dds::Qos(8), "robot.a");
  dds::Writer<lineloc_msg_LineSet> other(other_robot, dds::Qos(8), "robot.b");
  dds::Writer<lineloc_msg_LineSet> unpartitioned(other_robot, dds::Qos(8));
  dds::Reader<lineloc_msg_LineSet> every_robot(backbone, dds::Qos(8), "robot.*");
  dds::Reader<lineloc_msg_LineSet> robot_a_only(robot, dds::Qos(8), "robot.a");
  ASSERT_TRUE(waitFor([&] { return every_robot.matchedWriters() == 2; }));
  ASSERT_TRUE(waitFor([&] { return robot_a_only.matchedWriters() == 1; }));
  EXPECT_EQ(unpartitioned.matchedReaders(), 0u);
  EXPECT_EQ(other.matchedReaders(), 1u) << "robot.b is not robot.a";

  LineSetData sent;
  sent.robot_id = "a";
  sent.camera = {400, 400, 320, 240, 0, 640, 480};
  own.write(LineSetMessage(sent).message());
  sent.robot_id = "b";
  other.write(LineSetMessage(sent).message());
  std::map<std::string, std::vector<std::string>> partitions_by_robot;
  ASSERT_TRUE(waitFor([&] {
    every_robot.waitForData(10'000'000);
    every_robot.takeEach([&](const lineloc_msg_LineSet& m, const dds::SampleInfo& info) {
      partitions_by_robot[m.robot_id] = every_robot.writerPartitions(info.publication_handle);
    });
    return partitions_by_robot.size() == 2;
  }));
  EXPECT_EQ(partitions_by_robot["a"], std::vector<std::string>{"robot.a"});
  EXPECT_EQ(partitions_by_robot["b"], std::vector<std::string>{"robot.b"});
}

TEST(DdsLoopback, LineSetOf300SegmentsArrivesIntactBetweenParticipants) {
  dds::Domain domain(test::testDomainId(), test::testDdsConfig());
  dds::Participant sender_participant(domain);
  dds::Participant receiver_participant(domain);
  dds::Writer<lineloc_msg_LineSet> writer(sender_participant, dds::Qos(8));
  dds::Reader<lineloc_msg_LineSet> reader(receiver_participant, dds::Qos(8));
  ASSERT_TRUE(waitFor([&] { return writer.matchedReaders() == 1; }));
  EXPECT_EQ(reader.matchedWriters(), 1u);

  LineSetData sent;
  sent.robot_id = "loopback";
  sent.sequence_number = 7;
  sent.stamp_ns = wallClockNs();
  sent.camera = {400, 400, 320, 240, 0, 640, 480};
  for (int i = 0; i < 300; ++i) {
    ImageSegment segment;
    segment.start = {static_cast<float>(i), 1.0f};
    segment.end = {static_cast<float>(i), 400.0f};
    segment.polarity = 1;
    sent.segments.push_back(segment);
  }
  const LineSetMessage message(sent);
  writer.write(message.message());

  std::vector<LineSetData> received;
  ASSERT_TRUE(waitFor([&] {
    reader.waitForData(10'000'000);
    reader.takeEach([&](const lineloc_msg_LineSet& m) { received.push_back(fromMessage(m)); });
    return !received.empty();
  }));
  ASSERT_EQ(received.size(), 1u);
  EXPECT_EQ(received[0].robot_id, "loopback");
  EXPECT_EQ(received[0].sequence_number, 7u);
  EXPECT_EQ(received[0].stamp_ns, sent.stamp_ns);
  ASSERT_EQ(received[0].segments.size(), 300u);
  EXPECT_EQ(received[0].segments[299].start.x(), 299.0f);
}

TEST(DdsLoopback, ASampleCarriesWhenItsWriterWroteIt) {
  dds::Domain domain(test::testDomainId(), test::testDdsConfig());
  dds::Participant backbone(domain);
  dds::Participant robot(domain);
  dds::Writer<lineloc_msg_PoseFix> writer(backbone, dds::Qos(8));
  dds::Reader<lineloc_msg_PoseFix> reader(robot, dds::Qos(8));
  ASSERT_TRUE(waitFor([&] { return writer.matchedReaders() == 1; }));
  PoseFixData fix;
  fix.robot_id = "stamped";
  const int64_t before_write_ns = wallClockNs();
  writer.write(toMessage(fix));
  const int64_t after_write_ns = wallClockNs();
  std::vector<int64_t> source_stamps_ns;
  ASSERT_TRUE(waitFor([&] {
    reader.waitForData(10'000'000);
    reader.takeEach([&](const lineloc_msg_PoseFix&, const dds::SampleInfo& info) {
      source_stamps_ns.push_back(info.source_stamp_ns);
    });
    return !source_stamps_ns.empty();
  }));
  ASSERT_EQ(source_stamps_ns.size(), 1u);
  EXPECT_GE(source_stamps_ns[0], before_write_ns);
  EXPECT_LE(source_stamps_ns[0], after_write_ns);
}

// Writes fixes numbered 1..count for `robot_id` before any reader exists.
void writeFixesToNobody(dds::Writer<lineloc_msg_PoseFix>& writer, const std::string& robot_id,
                        uint32_t count) {
  for (uint32_t sequence = 1; sequence <= count; ++sequence) {
    PoseFixData fix;
    fix.robot_id = robot_id;
    fix.sequence_number = sequence;
    writer.write(toMessage(fix));
  }
}

std::vector<uint32_t> takeSequenceNumbers(dds::Reader<lineloc_msg_PoseFix>& reader) {
  std::vector<uint32_t> sequence_numbers;
  reader.takeEach(
      [&](const lineloc_msg_PoseFix& fix) { sequence_numbers.push_back(fix.sequence_number); });
  return sequence_numbers;
}

TEST(DdsLoopback, AnswersKeptForLateReadersReachAReaderTheWriterMeetsAfterWritingThem) {
  constexpr int32_t kDepth = 4;
  dds::Domain domain(test::testDomainId(), test::testDdsConfig());
  dds::Participant backbone(domain);
  dds::Writer<lineloc_msg_PoseFix> writer(backbone,
                                          dds::Qos::keptForLateReaders(kDepth, 10'000'000'000));
  writeFixesToNobody(writer, "late", 6);
  dds::Participant robot(domain);
  dds::Reader<lineloc_msg_PoseFix> kept_for(robot,
                                            dds::Qos::keptForLateReaders(kDepth, 10'000'000'000));
  dds::Reader<lineloc_msg_PoseFix> volatile_reader(robot, dds::Qos(kDepth));
  std::vector<uint32_t> received;
  ASSERT_TRUE(waitFor([&] {
    kept_for.waitForData(10'000'000);
    const std::vector<uint32_t> taken = takeSequenceNumbers(kept_for);
    received.insert(received.end(), taken.begin(), taken.end());
    return received.size() >= kDepth;
  })) << received.size()
      << " of the last " << kDepth << " answers arrived";
  EXPECT_EQ(received, (std::vector<uint32_t>{3, 4, 5, 6})) << "the robot's last kDepth answers";
  ASSERT_TRUE(waitFor([&] { return writer.matchedReaders() == 2; }));
  EXPECT_FALSE(volatile_reader.waitForData(200'000'000));
}

TEST(DdsLoopback, AnswersKeptForLateReadersAreGoneAfterTheirLifespan) {
  dds::Domain domain(test::testDomainId(), test::testDdsConfig());
  dds::Participant backbone(domain);
  dds::Writer<lineloc_msg_PoseFix> writer(backbone, dds::Qos::keptForLateReaders(8, 100'000'000));
  writeFixesToNobody(writer, "late", 3);
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  dds::Participant robot(domain);
  dds::Reader<lineloc_msg_PoseFix> reader(robot, dds::Qos::keptForLateReaders(8, 100'000'000));
  ASSERT_TRUE(waitFor([&] { return writer.matchedReaders() == 1; }));
  EXPECT_FALSE(reader.waitForData(300'000'000));
  EXPECT_TRUE(takeSequenceNumbers(reader).empty());
}

TEST(DdsLoopback, MissingConfigFileIsAClearError) {
  try {
    dds::Domain domain(test::testDomainId(), "/nonexistent/cyclonedds.xml");
    FAIL() << "a missing DDS config must throw";
  } catch (const std::runtime_error& error) {
    EXPECT_NE(std::string(error.what()).find("/nonexistent/cyclonedds.xml"), std::string::npos);
  }
}

TEST(DdsLoopback, AMissingConfigFileAmongSeveralIsNamed) {
  try {
    dds::Domain domain(test::testDomainId(), test::testDdsConfig() + ",/nonexistent/layer.xml");
    FAIL() << "a missing DDS config must throw";
  } catch (const std::runtime_error& error) {
    EXPECT_NE(std::string(error.what()).find("'/nonexistent/layer.xml'"), std::string::npos);
  }
}

TEST(DdsLoopback, ConfigFilesSeparatedByCommasAddToEachOther) {
  const fs::path work = fs::temp_directory_path() / ("dds_layers_" + std::to_string(getpid()));
  fs::create_directories(work);
  const fs::path trace = work / "trace.log";
  const fs::path layer = work / "trace.xml";
  std::ofstream(layer) << "<CycloneDDS xmlns=\"https://cdds.io/config\"><Domain id=\"any\">"
                          "<Tracing><Verbosity>config</Verbosity><OutputFile>"
                       << trace.string() << "</OutputFile></Tracing></Domain></CycloneDDS>\n";
  {
    // Another domain than the other tests': this process has not created it yet.
    dds::Domain domain(test::testDomainId() + 1, test::testDdsConfig() + "," + layer.string());
    dds::Participant participant(domain);
  }
  std::ifstream traced(trace);
  const std::string text((std::istreambuf_iterator<char>(traced)),
                         std::istreambuf_iterator<char>());
  fs::remove_all(work);
  // The second file's tracing, with the first file's loopback-only settings.
  EXPECT_NE(text.find("AllowMulticast"), std::string::npos) << text;
  EXPECT_NE(text.find("127.0.0.1"), std::string::npos) << text;
}

TEST(DdsLoopback, WaitTimesOutWithoutData) {
  dds::Domain domain(test::testDomainId(), test::testDdsConfig());
  dds::Participant participant(domain);
  dds::Reader<lineloc_msg_PoseFix> reader(participant, dds::Qos(8));
  EXPECT_FALSE(reader.waitForData(20'000'000));
  EXPECT_EQ(reader.takeEach([](const lineloc_msg_PoseFix&) {}), 0);
}

}  // namespace
}  // namespace lineloc
