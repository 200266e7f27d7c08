#include "robot/agent/robot_agent.h"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <thread>
#include <unordered_map>

#include "common/camera/camera_calibration.h"
#include "common/messages/message_validator.h"
#include "common/messages/messages.h"
#include "common/messages/topics.h"
#include "common/time/clock.h"
#include "common/trajectory/tum_trajectory.h"
#include "robot/input/image_sequence.h"
#include "robot/vision/features/feature_extractor.h"

namespace lineloc {
namespace {

constexpr int kHistoryDepth = 32;
constexpr int64_t kPollNs = 5'000'000;

PoseWithCovariance predictedPose(const RobotConfig& config) {
  const std::vector<double>& p = config.predicted_pose;
  if (p.size() != 7) {
    throw std::runtime_error("predicted_pose needs 7 numbers: tx ty tz qx qy qz qw");
  }
  const Eigen::Quaterniond q(p[6], p[3], p[4], p[5]);
  if (std::abs(q.norm() - 1.0) > 1e-3) {
    throw std::runtime_error("predicted_pose: quaternion is not of unit norm");
  }
  PoseWithCovariance pose;
  pose.pose = makePose({p[0], p[1], p[2]}, q);
  pose.covariance = diagonalPoseCovariance(config.predicted_position_sigma_m,
                                           config.predicted_rotation_sigma_deg * M_PI / 180.0);
  return pose;
}

// Receives PoseFix answers for one robot and records them.
class FixReceiver {
 public:
  FixReceiver(const dds::Participant& participant, const RobotConfig& config,
              RobotRunSummary& summary)
      : reader_(participant, dds::Qos(kHistoryDepth)),
        robot_id_(config.robot_id),
        trajectory_(config.trajectory_out),
        summary_(summary) {}

  void expect(uint32_t sequence_number) { sent_ns_[sequence_number] = steadyClockNs(); }
  size_t outstanding() const { return sent_ns_.size(); }

  void poll(int64_t timeout_ns) {
    if (reader_.waitForData(timeout_ns)) {
      reader_.takeEach([this](const lineloc_msg_PoseFix& fix) { receive(fix); });
    }
  }

 private:
  void receive(const lineloc_msg_PoseFix& message) {
    if (robot_id_ != message.robot_id) {
      return;  // another robot's answer
    }
    if (const auto error = findPoseFixError(message)) {
      ++summary_.fixes_dropped;
      spdlog::warn("dropped a malformed PoseFix: {}", *error);
      return;
    }
    const auto sent = sent_ns_.find(message.sequence_number);
    if (sent == sent_ns_.end()) {
      ++summary_.fixes_dropped;
      spdlog::warn("dropped a PoseFix for unknown or answered frame {}", message.sequence_number);
      return;
    }
    summary_.round_trip_ns.push_back(steadyClockNs() - sent->second);
    sent_ns_.erase(sent);
    const PoseFixData fix = fromMessage(message);
    ++summary_.fixes_received;
    ++summary_.fixes_by_status[toString(fix.status)];
    trajectory_.write({fix.stamp_ns, fix.T_world_camera.pose});
  }

  dds::Reader<lineloc_msg_PoseFix> reader_;
  std::string robot_id_;
  TumWriter trajectory_;
  RobotRunSummary& summary_;
  std::unordered_map<uint32_t, int64_t> sent_ns_;
};

void waitForBackbone(const dds::Writer<lineloc_msg_LineSet>& writer, double timeout_s,
                     const std::atomic<bool>& stop) {
  const int64_t deadline = steadyClockNs() + static_cast<int64_t>(timeout_s * 1e9);
  while (writer.matchedReaders() == 0 && steadyClockNs() < deadline && !stop) {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  if (writer.matchedReaders() == 0) {
    spdlog::warn("no backbone found after {:.1f} s; sending anyway", timeout_s);
  }
}

}  // namespace

int64_t percentile(std::vector<int64_t> values, double percent) {
  if (values.empty()) {
    return 0;
  }
  const size_t rank = static_cast<size_t>(std::ceil(percent / 100.0 * values.size()));
  const size_t index = std::clamp<size_t>(rank, 1, values.size()) - 1;
  std::nth_element(values.begin(), values.begin() + index, values.end());
  return values[index];
}

RobotRunSummary runRobot(const RobotConfig& config, const std::atomic<bool>& stop) {
  if (!isValidRobotId(config.robot_id)) {
    throw std::runtime_error(fmt::format(
        "robot_id '{}' must match [A-Za-z0-9][A-Za-z0-9_.-]* (at most 32 characters)",
        config.robot_id));
  }
  if (config.calibration.empty()) {
    throw std::runtime_error("calibration: a camera calibration file is required");
  }
  const CameraCalibration calibration = readCameraCalibration(config.calibration);
  const PoseWithCovariance predicted = predictedPose(config);
  std::vector<FrameRef> frames = listImageSequence(config.images);
  if (config.max_frames > 0 && static_cast<int>(frames.size()) > config.max_frames) {
    frames.resize(config.max_frames);
  }
  FeatureExtractorOptions extractor_options;
  extractor_options.lines.min_length_px = config.min_segment_length_px;
  FeatureExtractor extractor(calibration, extractor_options);

  dds::Domain domain(config.domain_id, config.dds_config);
  dds::Participant participant(domain);
  RobotRunSummary summary;
  FixReceiver receiver(participant, config, summary);
  dds::Writer<lineloc_msg_LineSet> writer(participant, dds::Qos(kHistoryDepth));
  waitForBackbone(writer, config.wait_for_backbone_s, stop);

  const int64_t period_ns = config.rate_hz > 0.0 ? static_cast<int64_t>(1e9 / config.rate_hz) : 0;
  int64_t next_frame_ns = steadyClockNs();
  for (size_t index = 0; index < frames.size() && !stop; ++index) {
    while (steadyClockNs() < next_frame_ns && !stop) {
      receiver.poll(std::min(kPollNs, next_frame_ns - steadyClockNs()));
    }
    next_frame_ns += period_ns;
    const int64_t capture_ns = wallClockNs();
    LineSetData line_set;
    line_set.robot_id = config.robot_id;
    line_set.sequence_number = static_cast<uint32_t>(index);
    line_set.stamp_ns = frames[index].stamp_ns.value_or(capture_ns);
    line_set.camera = calibration.camera;
    const FrameFeatures& features = extractor.extract(readGreyImage(frames[index].path));
    line_set.segments = features.segments;
    line_set.corners = features.corners;
    line_set.predicted_T_world_camera = predicted;
    const LineSetMessage message(line_set);
    receiver.expect(line_set.sequence_number);
    writer.write(message.message());
    ++summary.frames_sent;
    receiver.poll(0);
  }
  const int64_t deadline = steadyClockNs() + static_cast<int64_t>(config.fix_timeout_s * 1e9);
  while (receiver.outstanding() > 0 && steadyClockNs() < deadline && !stop) {
    receiver.poll(kPollNs);
  }
  return summary;
}

}  // namespace lineloc
