#include "backbone/service/hypothesis_set.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <utility>

namespace lineloc {

PoseOffset PoseOffset::between(const Eigen::Isometry3d& from, const Eigen::Isometry3d& to) {
  return {(to.translation() - from.translation()).norm(),
          std::abs(Eigen::AngleAxisd(from.linear().transpose() * to.linear()).angle())};
}

PoseOffset PoseOffset::farthest(const PoseOffset& other) const {
  return {std::max(position_m, other.position_m), std::max(rotation_rad, other.rotation_rad)};
}

bool PoseOffset::within(const PoseOffset& limit) const {
  return position_m <= limit.position_m && rotation_rad <= limit.rotation_rad;
}

HypothesisSet::HypothesisSet(const HypothesisSetOptions& options) : options_(options) {}

void HypothesisSet::clear() {
  keyframes_.clear();
  last_.reset();
  hypotheses_.clear();
}

std::vector<Eigen::Isometry3d> HypothesisSet::carriedStarts(const OdometryPose& odometry) const {
  std::vector<Eigen::Isometry3d> starts;
  if (!last_ || last_->odometry.epoch != odometry.epoch) {
    return starts;
  }
  for (const Hypothesis& hypothesis : hypotheses_) {
    starts.push_back(hypothesis.latest.T_world_camera.pose *
                     motionBetween(last_->odometry, odometry));
  }
  return starts;
}

std::vector<Eigen::Isometry3d> HypothesisSet::latestPoses() const {
  std::vector<Eigen::Isometry3d> poses;
  for (const Hypothesis& hypothesis : hypotheses_) {
    poses.push_back(hypothesis.latest.T_world_camera.pose);
  }
  return poses;
}

bool HypothesisSet::startsView(const SearchedFrame& frame) const {
  if (keyframes_.empty()) {
    return true;
  }
  const PoseOffset motion =
      PoseOffset::between(keyframes_.back().odometry.T_odom_camera, frame.odometry.T_odom_camera);
  return motion.position_m >= options_.view_spacing_m ||
         motion.rotation_rad >= options_.view_spacing_rad;
}

uint64_t HypothesisSet::slideWindow(const SearchedFrame& frame) {
  const auto window_ns = static_cast<int64_t>(options_.window_s * 1e9);
  while (!keyframes_.empty() && frame.stamp_ns - keyframes_.front().stamp_ns > window_ns) {
    keyframes_.pop_front();
  }
  if (startsView(frame)) {
    keyframes_.push_back(frame);
    if (static_cast<int>(keyframes_.size()) > options_.max_views) {
      keyframes_.pop_front();
    }
  }
  const std::vector<uint64_t> kept = windowFrames();
  for (Hypothesis& hypothesis : hypotheses_) {
    std::erase_if(hypothesis.views, [&](const auto& view) {
      return std::ranges::find(kept, view.first) == kept.end();
    });
  }
  return keyframes_.back().id;
}

std::vector<uint64_t> HypothesisSet::windowFrames() const {
  std::vector<uint64_t> ids;
  for (const SearchedFrame& keyframe : keyframes_) {
    ids.push_back(keyframe.id);
  }
  return ids;
}

void HypothesisSet::add(const SearchedFrame& frame, const std::vector<ScoredHypothesis>& aligned,
                        const Rescore& rescore) {
  const auto window_ns = static_cast<int64_t>(options_.window_s * 1e9);
  if (last_ &&
      (last_->odometry.epoch != frame.odometry.epoch || frame.stamp_ns <= last_->stamp_ns ||
       frame.stamp_ns - last_->stamp_ns > window_ns)) {
    clear();
  }
  const std::vector<Eigen::Isometry3d> carried = carriedStarts(frame.odometry);
  const uint64_t view = slideWindow(frame);
  last_ = frame;

  // Each hypothesis takes the alignment from its own carried start, else the
  // nearest one, when it settled within `same` of where the robot's motion
  // moved it; otherwise it did not align here.
  std::vector<bool> taken(aligned.size(), false);
  for (size_t i = 0; i < hypotheses_.size(); ++i) {
    Hypothesis& hypothesis = hypotheses_[i];
    std::optional<size_t> chosen;
    double chosen_m = options_.same.position_m;
    for (size_t j = 0; j < aligned.size(); ++j) {
      const PoseOffset offset = PoseOffset::between(carried[i], aligned[j].T_world_camera.pose);
      if (!offset.within(options_.same)) {
        continue;
      }
      if (aligned[j].carried_index == static_cast<int>(i)) {
        chosen = j;
        break;
      }
      if (offset.position_m <= chosen_m) {
        chosen = j;
        chosen_m = offset.position_m;
      }
    }
    if (chosen) {
      hypothesis.latest = aligned[*chosen];
      taken[*chosen] = true;
      const bool proposed = std::ranges::any_of(aligned, [&](const ScoredHypothesis& other) {
        return other.carried_index < 0 &&
               PoseOffset::between(other.T_world_camera.pose, hypothesis.latest.T_world_camera.pose)
                   .within(options_.same);
      });
      hypothesis.proposed += proposed ? 1 : 0;
    } else {
      hypothesis.latest.T_world_camera.pose = carried[i];
      hypothesis.latest.status = AlignmentStatus::kFailed;
      hypothesis.latest.score = 0.0;
      hypothesis.latest.inliers = 0;
    }
    ViewScore& score = hypothesis.views[view];
    score.sum += hypothesis.latest.score;
    ++score.frames;
  }

  // The others, best first, are new hypotheses unless one already holds
  // their pose; each is scored in the earlier views' keyframes too.
  std::vector<size_t> order;
  for (size_t j = 0; j < aligned.size(); ++j) {
    order.push_back(j);
  }
  std::ranges::sort(order, [&](size_t a, size_t b) { return aligned[a].score > aligned[b].score; });
  for (const size_t j : order) {
    const ScoredHypothesis& found = aligned[j];
    const bool known =
        taken[j] || std::ranges::any_of(hypotheses_, [&](const Hypothesis& other) {
          return PoseOffset::between(other.latest.T_world_camera.pose, found.T_world_camera.pose)
              .within(options_.same);
        });
    if (known) {
      continue;
    }
    Hypothesis hypothesis{found, {{view, {found.score, 1}}}, found.carried_index < 0 ? 1 : 0, 0.0};
    for (const SearchedFrame& keyframe : keyframes_) {
      if (keyframe.id == view) {
        continue;
      }
      // There only when it settles within `same` of where the motion puts it.
      const Eigen::Isometry3d start =
          found.T_world_camera.pose * motionBetween(frame.odometry, keyframe.odometry);
      const std::optional<ScoredHypothesis> there = rescore(keyframe.id, start);
      const bool settled_there =
          there && PoseOffset::between(start, there->T_world_camera.pose).within(options_.same);
      hypothesis.views[keyframe.id] = {settled_there ? there->score : 0.0, 1};
    }
    hypotheses_.push_back(std::move(hypothesis));
  }
  latest_aligned_ = aligned;
  weigh();
}

void HypothesisSet::weigh() {
  const double kappa = options_.evidence_per_view;
  none_evidence_ = 0.0;
  free_evidence_ = 0.0;
  for (Hypothesis& hypothesis : hypotheses_) {
    hypothesis.evidence = 0.0;
  }
  for (const uint64_t view : windowFrames()) {
    double view_best = 0.0;
    for (const Hypothesis& hypothesis : hypotheses_) {
      const auto score = hypothesis.views.find(view);
      if (score != hypothesis.views.end()) {
        view_best = std::max(view_best, score->second.mean());
      }
    }
    const double reference = std::max(options_.none_score, view_best);  // s*_v
    none_evidence_ += kappa * options_.none_score / reference;
    free_evidence_ += kappa * view_best / reference;
    for (Hypothesis& hypothesis : hypotheses_) {
      const auto score = hypothesis.views.find(view);
      if (score != hypothesis.views.end()) {
        hypothesis.evidence += kappa * score->second.mean() / reference;
      }
    }
  }
  std::ranges::stable_sort(hypotheses_, std::greater<>(), &Hypothesis::evidence);
  // Two hypotheses that settled on one pose are one: the likelier stays.
  std::vector<Hypothesis> distinct;
  for (Hypothesis& hypothesis : hypotheses_) {
    const bool same_as_likelier = std::ranges::any_of(distinct, [&](const Hypothesis& kept) {
      return PoseOffset::between(kept.latest.T_world_camera.pose,
                                 hypothesis.latest.T_world_camera.pose)
          .within(options_.same);
    });
    if (!same_as_likelier) {
      distinct.push_back(std::move(hypothesis));
    }
  }
  hypotheses_ = std::move(distinct);
  if (static_cast<int>(hypotheses_.size()) > options_.max_hypotheses) {
    hypotheses_.resize(options_.max_hypotheses);
  }
}

bool HypothesisSet::leadsEveryView(const Hypothesis& hypothesis) const {
  if (static_cast<int>(keyframes_.size()) < options_.max_views) {
    return false;
  }
  for (const uint64_t view : windowFrames()) {
    const auto own = hypothesis.views.find(view);
    if (own == hypothesis.views.end() || own->second.mean() < options_.none_score) {
      return false;
    }
    for (const Hypothesis& other : hypotheses_) {
      const auto score = other.views.find(view);
      if (&other != &hypothesis && score != other.views.end() &&
          score->second.mean() > own->second.mean()) {
        return false;
      }
    }
  }
  return true;
}

std::optional<HypothesisDecision> HypothesisSet::decision(
    int min_inliers, const std::function<bool(const PoseWithCovariance&)>& trackable,
    std::string* undecided) const {
  if (hypotheses_.empty()) {
    if (undecided != nullptr) {
      *undecided = "no hypothesis";
    }
    return std::nullopt;
  }
  const Hypothesis& best = hypotheses_.front();
  const ScoredHypothesis& latest = best.latest;
  // p_h = exp(E_h - E_best) / sum over "none" and every hypothesis.
  double normaliser = std::exp(none_evidence_ - best.evidence);
  for (const Hypothesis& hypothesis : hypotheses_) {
    normaliser += std::exp(hypothesis.evidence - best.evidence);
  }
  HypothesisDecision decision{best.latest, 1.0 / normaliser, {}};
  const auto undecidedBecause = [&](const std::string& why) -> std::optional<HypothesisDecision> {
    if (undecided != nullptr) {
      const Eigen::Vector3d& position = latest.T_world_camera.pose.translation();
      *undecided = fmt::format(
          "the likeliest, at ({:.2f}, {:.2f}) m, posterior {:.4f} over {} views, proposed by {} "
          "grids, {}",
          position.x(), position.y(), decision.posterior, keyframes_.size(), best.proposed, why);
    }
    return std::nullopt;
  };
  if (best.proposed < 2 && !leadsEveryView(best)) {
    return undecidedBecause("was neither proposed by two frames' grids nor led every view");
  }
  if (latest.status != AlignmentStatus::kOk || latest.inliers < min_inliers ||
      latest.score < options_.none_score) {
    return undecidedBecause(
        fmt::format("aligned in the latest frame with {} inliers "
                    "and score {:.1f}, not OK",
                    latest.inliers, latest.score));
  }
  const bool outscored = std::ranges::any_of(latest_aligned_, [&](const ScoredHypothesis& other) {
    return other.score > latest.score &&
           !PoseOffset::between(other.T_world_camera.pose, latest.T_world_camera.pose)
                .within(options_.same);
  });
  if (outscored) {
    return undecidedBecause("was outscored in the latest frame");
  }
  if (decision.posterior < options_.min_posterior) {
    return undecidedBecause("is not likely enough");
  }
  // Each frame explained by a pose of its own, against the one hypothesis
  // moved by the robot's motion: views that no one pose explains (the
  // robot's motion is not what its odometry says) take none.
  const double min_odds = options_.min_posterior / (1.0 - options_.min_posterior);
  if (free_evidence_ - best.evidence > std::log(min_odds)) {
    return undecidedBecause("does not explain the views as their own poses do");
  }
  if (!trackable(best.latest.T_world_camera) &&
      static_cast<int>(keyframes_.size()) < options_.min_wide_views) {
    return undecidedBecause("is too wide to track from one view");
  }
  for (size_t i = 1; i < hypotheses_.size(); ++i) {
    if (std::exp(hypotheses_[i].evidence - best.evidence) / normaliser >=
        options_.covered_posterior) {
      decision.covered = decision.covered.farthest(PoseOffset::between(
          best.latest.T_world_camera.pose, hypotheses_[i].latest.T_world_camera.pose));
    }
  }
  return decision;
}

}  // namespace lineloc
