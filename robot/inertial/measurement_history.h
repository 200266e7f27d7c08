// The navigation filter's recent past (navigation_filter.h), kept so that a
// measurement updates the filter at its own time however late it comes.
//
// Every IMU sample leaves a snapshot (state, covariance, sample) in a history
// of `history_ns`; every measurement is kept, in time order, for as long as
// its time is inside that history. A measurement whose time is already past
// rewinds to the last snapshot before it and replays the IMU samples and
// measurements after it, splitting the IMU interval at each measurement's
// time (rates interpolated linearly):
//   t_k < t_m < t_k+1:  w(t_m) = w_k + (w_k+1 - w_k) (t_m - t_k) / (t_k+1 - t_k),
// likewise the specific force. A measurement whose time is still ahead waits
// until the IMU reaches it. Both paths run the same arithmetic, so a fix
// delivered 300 ms late gives the same state as one delivered on time.
//
// Each measurement is counted once, by its latest outcome: a replay that
// changes it moves its count.
#pragma once

#include <array>
#include <cstdint>
#include <deque>
#include <map>
#include <optional>
#include <utility>
#include <vector>

#include "robot/inertial/imu_sample.h"
#include "robot/inertial/navigation_filter.h"
#include "robot/inertial/navigator_measurements.h"

namespace lineloc {

// An IMU sample, and whether the IMU was still over the window up to it
// (for zero-velocity updates).
struct BufferedImu {
  ImuSample sample;
  bool still = false;
};

class MeasurementHistory {
 public:
  explicit MeasurementHistory(int64_t history_ns);

  // Buffers `imu` (stamps increasing); once started, steps the filter to it.
  void addImu(const BufferedImu& imu, const NavigationFilter& filter);
  // Drops every snapshot and measurement, starts the filter at `snapshot` and
  // steps it through the samples buffered after its time.
  void start(const FilterSnapshot& snapshot, const NavigationFilter& filter);
  bool started() const { return !snapshots_.empty(); }

  // Keeps `measurement` and, when the IMU has passed its time, replays from
  // there. Returns its outcome, kPending while the IMU has not reached it, or
  // kTooLate (not kept) at or before the oldest snapshot. Requires started().
  MeasurementOutcome add(int64_t stamp_ns, Measurement measurement, const NavigationFilter& filter);

  // Drops the snapshots, samples and measurements older than history_ns
  // before the newest sample, keeping one sample at or before the oldest
  // snapshot; returns the measurements dropped, oldest first, their outcomes
  // final. Requires a buffered sample.
  std::vector<std::pair<int64_t, Measurement>> prune();

  // Require started().
  const FilterSnapshot& oldest() const { return snapshots_.front(); }
  const FilterSnapshot& latest() const { return snapshots_.back(); }
  // The last snapshot at or before `stamp_ns`, else the oldest.
  const FilterSnapshot& at(int64_t stamp_ns) const;
  // The filter at `stamp_ns`, at or after the oldest snapshot: the last
  // snapshot before it propagated with the rates interpolated to the next
  // sample, or past the latest, holding the latest sample's rates.
  FilterSnapshot predict(int64_t stamp_ns, const NavigationFilter& filter) const;

  // The measurements kept, in time order.
  const std::multimap<int64_t, Measurement>& measurements() const { return measurements_; }
  // Counted by their latest outcome, kept or dropped since construction.
  const MeasurementCounters& counters(MeasurementKind kind) const {
    return counters_[static_cast<size_t>(kind)];
  }

  // The newest sample buffered; nullopt before any.
  std::optional<ImuSample> latestImu() const;
  // The buffered reading at `stamp_ns` (imuAt, imu_sample.h).
  std::optional<ImuSample> imuAt(int64_t stamp_ns) const;
  // The buffered readings over [from_stamp_ns, to_stamp_ns] (imuOver, imu_sample.h).
  std::optional<std::vector<ImuSample>> imuOver(int64_t from_stamp_ns, int64_t to_stamp_ns) const;

 private:
  // Steps the latest snapshot to `imu` through the measurements between them.
  void step(const BufferedImu& imu, const NavigationFilter& filter);
  // Drops the snapshots after `snapshot_index` and steps through the samples after it again.
  void replayFrom(size_t snapshot_index, const NavigationFilter& filter);
  void record(Measurement& measurement, MeasurementOutcome outcome);
  // The first snapshot after `stamp_ns`.
  std::deque<FilterSnapshot>::const_iterator after(int64_t stamp_ns) const;

  int64_t history_ns_;
  std::deque<BufferedImu> imu_;
  std::deque<FilterSnapshot> snapshots_;
  std::multimap<int64_t, Measurement> measurements_;
  std::array<MeasurementCounters, kMeasurementKinds> counters_{};
};

}  // namespace lineloc
