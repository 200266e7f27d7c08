#include "backbone/service/acquisition_session.h"

#include <algorithm>
#include <utility>

namespace lineloc {

AcquisitionSession::AcquisitionSession(const HypothesisSetOptions& options)
    : window_ns_(static_cast<int64_t>(options.window_s * 1e9)), hypotheses_(options) {}

void AcquisitionSession::clear() {
  hypotheses_.clear();
  frames_.clear();
  const std::lock_guard<std::mutex> lock(handed_mutex_);
  handed_ = {};
  adopted_.reset();
}

HandedHypotheses AcquisitionSession::handed() const {
  const std::lock_guard<std::mutex> lock(handed_mutex_);
  return handed_;
}

void AcquisitionSession::adopt(HandedHypotheses hypotheses) {
  const std::lock_guard<std::mutex> lock(handed_mutex_);
  adopted_ = std::move(hypotheses);
}

std::vector<Eigen::Isometry3d> AcquisitionSession::adoptedStarts(const LineSetData& line_set) {
  std::optional<HandedHypotheses> adopted;
  {
    const std::lock_guard<std::mutex> lock(handed_mutex_);
    adopted.swap(adopted_);
  }
  std::vector<Eigen::Isometry3d> starts;
  if (!adopted || hypotheses_.size() > 0 || adopted->stamp_ns > line_set.stamp_ns ||
      line_set.stamp_ns - adopted->stamp_ns > window_ns_) {
    return starts;
  }
  for (const Eigen::Isometry3d& T_prediction_camera : adopted->T_prediction_camera) {
    starts.push_back(line_set.predicted_T_world_camera.pose * T_prediction_camera);
  }
  return starts;
}

AcquisitionSession::Searched AcquisitionSession::search(const LineSetData& line_set,
                                                        const OdometryPose& odometry,
                                                        std::shared_ptr<const PreparedMap> map,
                                                        const PoseWithCovariance& prior,
                                                        const LocalizerOptions& options) {
  const AcquisitionOptions& acquisition = options.acquisition;
  Searched searched;
  std::vector<Eigen::Isometry3d> carried = adoptedStarts(line_set);
  if (carried.empty()) {
    carried = hypotheses_.carriedStarts(odometry);
  }
  searched.acquisition = acquirePose(line_set.segments, map->segments, map->scene, prior,
                                     line_set.camera, acquisition, carried);
  const SearchedFrame frame{next_frame_id_++, line_set.stamp_ns, odometry};
  frames_.emplace(frame.id, Frame{line_set.segments, line_set.camera, prior, std::move(map),
                                  searched.acquisition.summary.sky_clutter_density});
  hypotheses_.add(frame, searched.acquisition.summary.aligned_hypotheses,
                  [&](uint64_t frame_id, const Eigen::Isometry3d& start) {
                    const Frame& earlier = frames_.at(frame_id);
                    return alignHypothesis(earlier.segments, earlier.map->segments,
                                           earlier.map->scene, earlier.prior, start, earlier.camera,
                                           earlier.sky_clutter_density, acquisition);
                  });
  const std::vector<uint64_t> window = hypotheses_.windowFrames();
  std::erase_if(frames_, [&](const auto& kept) {
    return std::ranges::find(window, kept.first) == window.end();
  });
  searched.decision = hypotheses_.decision(
      acquisition.min_inliers,
      [&](const PoseWithCovariance& pose) { return !needsAcquisition(pose, options); },
      &searched.undecided);
  searched.hypotheses = hypotheses_.size();
  HandedHypotheses handed{line_set.stamp_ns, {}};
  const Eigen::Isometry3d T_prediction_world = line_set.predicted_T_world_camera.pose.inverse();
  for (const Eigen::Isometry3d& T_world_camera : hypotheses_.latestPoses()) {
    handed.T_prediction_camera.push_back(T_prediction_world * T_world_camera);
  }
  const std::lock_guard<std::mutex> lock(handed_mutex_);
  handed_ = std::move(handed);
  return searched;
}

}  // namespace lineloc
