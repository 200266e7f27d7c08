#include "backbone/service/acquisition_session.h"

#include <algorithm>
#include <utility>

namespace lineloc {

AcquisitionSession::AcquisitionSession(const HypothesisSetOptions& options)
    : hypotheses_(options) {}

void AcquisitionSession::clear() {
  hypotheses_.clear();
  frames_.clear();
}

AcquisitionSession::Searched AcquisitionSession::search(const LineSetData& line_set,
                                                        const OdometryPose& odometry,
                                                        std::shared_ptr<const PreparedMap> map,
                                                        const PoseWithCovariance& prior,
                                                        const LocalizerOptions& options) {
  const AcquisitionOptions& acquisition = options.acquisition;
  Searched searched;
  searched.acquisition =
      acquirePose(line_set.segments, map->segments, map->scene, prior, line_set.camera, acquisition,
                  hypotheses_.carriedStarts(odometry));
  const SearchedFrame frame{next_frame_id_++, line_set.stamp_ns, odometry};
  frames_.emplace(frame.id, Frame{line_set.segments, line_set.camera, prior, std::move(map)});
  hypotheses_.add(frame, searched.acquisition.summary.aligned_hypotheses,
                  [&](uint64_t frame_id, const Eigen::Isometry3d& start) {
                    const Frame& earlier = frames_.at(frame_id);
                    return alignHypothesis(earlier.segments, earlier.map->segments,
                                           earlier.map->scene, earlier.prior, start, earlier.camera,
                                           acquisition);
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
  return searched;
}

}  // namespace lineloc
