#include "backbone/service/fix_scatter.h"

#include <vector>

namespace lineloc {

FixScatter::FixScatter(const FixScatterOptions& options) : options_(options) {}

void FixScatter::forgetOlderThan(int64_t stamp_ns, uint64_t epoch) {
  const auto window_ns = static_cast<int64_t>(options_.window_s * 1e9);
  while (!recent_.empty() && (recent_.front().odometry.epoch != epoch ||
                              recent_.front().stamp_ns < stamp_ns - window_ns)) {
    recent_.pop_front();
  }
}

PoseWithCovariance FixScatter::floorAndAdd(int64_t stamp_ns, const OdometryPose& odometry,
                                           const PoseWithCovariance& answer) {
  forgetOlderThan(stamp_ns, odometry.epoch);
  PoseWithCovariance floored = answer;
  if (static_cast<int>(recent_.size()) >= options_.min_answers) {
    // Differences from the answer, whose own is zero: d_i = answer^-1 (A_i O_i^-1 O);
    // their sample covariance is their scatter over n - 1 = recent_.size().
    std::vector<Eigen::Matrix<double, 6, 1>> differences(1, Eigen::Matrix<double, 6, 1>::Zero());
    for (const RecentAnswer& recent : recent_) {
      const Eigen::Isometry3d moved =
          recent.T_world_camera * motionBetween(recent.odometry, odometry);
      differences.push_back(poseError(answer.pose, moved));
    }
    floored.covariance = coveringCovariance(
        answer.covariance, scatterAboutMean(differences) / static_cast<double>(recent_.size()));
  }
  recent_.push_back({stamp_ns, odometry, answer.pose});
  return floored;
}

}  // namespace lineloc
