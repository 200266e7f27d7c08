// Acquisition as one sequential estimator over several frames: the camera
// poses a robot's searches align (pose_acquisition.h) are kept as
// hypotheses, moved from frame to frame by the robot's own motion
// (predicted_motion.h: dead reckoning errs by centimetres over seconds, DGPS
// by metres), aligned again in every searched frame, and weighed by the
// evidence of a window of frames jointly: a multiple-hypothesis test in the
// sense of Reid ("An algorithm for tracking multiple targets", IEEE TAC
// 24(6), 1979), over poses instead of tracks.
//
// Views. Frames one view apart are independent evidence; a robot that stands
// still sees one view again and again, its frames differing by image noise
// only. The frames are therefore grouped into views: a frame starts a new
// view when the robot has moved at least view_spacing_m or turned
// view_spacing_rad since the frame that started the last one (the view's
// keyframe); the window holds the last max_views views, none older than
// window_s. A hypothesis's score in a view, s_{h,v}, is the mean of its
// verification scores s = (C - K) / sqrt(L) in the view's frames
// (pose_acquisition.h; 0 in a frame where it did not align).
//
// Evidence. Scores grow with the model in view, so each view's count
// relative to the view's best, and that is taken as a log-likelihood up to
// the scale kappa = evidence_per_view:
//
//   E_h = kappa sum_{v in window} s_{h,v} / s*_v,  s*_v = max(none_score, max_j s_{j,v}).
//
// Beside the hypotheses stands "none of them" (the camera at a pose no search
// has aligned), scoring none_score in every view: E_0 = kappa sum_v
// none_score / s*_v. The posterior of a hypothesis is
//
//   p_h = exp(E_h) / (exp(E_0) + sum_j exp(E_j)).
//
// A hypothesis found in a later view is aligned and scored in the earlier
// views' keyframes too (moved back by the robot's motion), so that every
// hypothesis is weighed on every view.
//
// The decision. The likeliest hypothesis is taken when its posterior is at
// least min_posterior; when it explains the views nearly as well as each
// view's own best pose does, exp(E_free - E_h) at most the odds
// min_posterior / (1 - min_posterior), with E_free = kappa sum_v max_j
// s_{j,v} / s*_v (else the views fit no one pose moved by the robot's
// motion: its odometry is wrong); when the searches' grids proposed it in at
// least two frames, not only the robot's motion (a local alignment from a
// carried pose settles in whatever basin holds it, right or wrong, so only a
// search that finds it again from afar confirms it), or it led every view of
// a full window (max_views views, the robot's motion between each: a wrong
// basin that one view's alignment settles in rarely stays the best pose of
// views seen from metres apart); when in the latest frame
// no pose elsewhere scores above it, and it aligned well-conditioned with at least
// min_inliers inliers (AcquisitionOptions::min_inliers) and a score of at
// least none_score; and, when that alignment is too wide to track from (the
// view fixes the pose poorly), when the window holds min_wide_views views.
// The other hypotheses still holding covered_posterior are the ambiguity the
// answer must cover: the farthest one's offset is returned with it. A
// standing robot whose view cannot tell its hypotheses apart is undecided
// until it moves.
#pragma once

#include <Eigen/Geometry>
#include <cstdint>
#include <deque>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "backbone/matching/pose_acquisition.h"
#include "backbone/service/predicted_motion.h"

namespace lineloc {

// How far one camera pose lies from another: the distance between the two
// and the angle of the rotation between them.
struct PoseOffset {
  double position_m = 0.0;
  double rotation_rad = 0.0;
  static PoseOffset between(const Eigen::Isometry3d& from, const Eigen::Isometry3d& to);
  // Each of the two at the larger of its own and `other`'s.
  PoseOffset farthest(const PoseOffset& other) const;
  // Whether both are within `limit`'s.
  bool within(const PoseOffset& limit) const;
};

struct HypothesisSetOptions {
  // kappa: the log-likelihood of a view's best score. One view then takes a
  // best whose one rival scores at most about 0.7 of it.
  double evidence_per_view = 16.0;
  // The score of "none of the hypotheses" in a frame: a pose that covers the
  // image no better is no answer (AcquisitionOptions::min_verification_score).
  double none_score = 5.0;
  double min_posterior = 0.99;
  // Hypotheses at least this likely are covered by the answer.
  double covered_posterior = 1e-3;
  // Two aligned poses closer than both of these are one hypothesis.
  PoseOffset same = {0.3, 0.5 * M_PI / 180.0};
  // The robot's motion from one view's keyframe to the next view.
  double view_spacing_m = 0.5;
  double view_spacing_rad = 5.0 * M_PI / 180.0;
  int max_views = 4;
  int max_hypotheses = 8;
  // Views a hypothesis too wide to track from must be seen from.
  int min_wide_views = 2;
  // A view whose keyframe is this old leaves the window; a robot searched
  // for again after this long starts afresh.
  double window_s = 10.0;
};

// The hypotheses a backbone hands over to one that takes its robot over
// (tracking_handovers.h): each the camera pose relative to the predicted pose
// of the frame searched at stamp_ns, T_prediction_camera =
// T_world_prediction^-1 T_world_camera, likeliest first.
struct HandedHypotheses {
  int64_t stamp_ns = 0;
  std::vector<Eigen::Isometry3d> T_prediction_camera;
};

// A searched frame of the robot: its id (the caller's key to the frame's
// data), exposure stamp and odometry pose.
struct SearchedFrame {
  uint64_t id = 0;
  int64_t stamp_ns = 0;
  OdometryPose odometry;
};

// A hypothesis taken as the camera's pose.
struct HypothesisDecision {
  ScoredHypothesis hypothesis;
  double posterior = 0.0;
  // The farthest of the other hypotheses holding covered_posterior.
  PoseOffset covered;
};

class HypothesisSet {
 public:
  // Aligns and scores a hypothesis in the window's frame `frame_id` from the
  // start `T_world_camera` (acquirePose's carried starts, one at a time);
  // nullopt when it does not align there.
  using Rescore = std::function<std::optional<ScoredHypothesis>(
      uint64_t frame_id, const Eigen::Isometry3d& T_world_camera)>;

  explicit HypothesisSet(const HypothesisSetOptions& options = {});

  // Every hypothesis moved by the robot's motion to `odometry`, in the order
  // of their ScoredHypothesis::carried_index in add(); none when `odometry`
  // starts a new chain.
  std::vector<Eigen::Isometry3d> carriedStarts(const OdometryPose& odometry) const;

  // Weighs the searched `frame` in: `aligned` are its search's aligned
  // hypotheses, those from carriedStarts(frame.odometry) included.
  // `rescore` scores new hypotheses in the earlier views' keyframes.
  void add(const SearchedFrame& frame, const std::vector<ScoredHypothesis>& aligned,
           const Rescore& rescore);

  // The hypothesis to take now, if one is (see above); `trackable` tells
  // whether an alignment is narrow enough to track from. When none is,
  // `undecided`, if given, says why the likeliest is not, for the log.
  std::optional<HypothesisDecision> decision(
      int min_inliers, const std::function<bool(const PoseWithCovariance&)>& trackable,
      std::string* undecided = nullptr) const;

  // The keyframes of the window's views, oldest first: the frames whose data
  // a caller keeps for `rescore`.
  std::vector<uint64_t> windowFrames() const;
  // Each hypothesis's pose in the latest frame, likeliest first.
  std::vector<Eigen::Isometry3d> latestPoses() const;
  size_t size() const { return hypotheses_.size(); }
  void clear();

 private:
  // A hypothesis's scores in one view: s_{h,v} = sum / frames.
  struct ViewScore {
    double sum = 0.0;
    int frames = 0;
    double mean() const { return sum / frames; }
  };
  struct Hypothesis {
    // Its alignment in the latest frame (moved there when it did not align).
    ScoredHypothesis latest;
    // Its scores in each view, by the view's keyframe.
    std::map<uint64_t, ViewScore> views;
    // Frames whose search's grid proposed it.
    int proposed = 0;
    double evidence = 0.0;
  };

  // Whether the window holds max_views views and `hypothesis` scored at least
  // none_score and no less than any other hypothesis in each of them.
  bool leadsEveryView(const Hypothesis& hypothesis) const;
  // Whether `frame` starts a new view.
  bool startsView(const SearchedFrame& frame) const;
  // Drops the views that leave the window when `frame` joins it; returns
  // the keyframe of the view it joins.
  uint64_t slideWindow(const SearchedFrame& frame);
  // Each hypothesis's E_h over the window, and E_0 and E_free; the
  // hypotheses kept at max_hypotheses, likeliest first.
  void weigh();

  HypothesisSetOptions options_;
  std::deque<SearchedFrame> keyframes_;  // one per view, oldest first
  std::optional<SearchedFrame> last_;    // the latest frame added
  std::vector<Hypothesis> hypotheses_;
  std::vector<ScoredHypothesis> latest_aligned_;  // the latest frame's
  double none_evidence_ = 0.0;                    // E_0
  double free_evidence_ = 0.0;                    // E_free
};

}  // namespace lineloc
