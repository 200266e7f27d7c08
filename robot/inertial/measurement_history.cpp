#include "robot/inertial/measurement_history.h"

#include <algorithm>
#include <iterator>

namespace lineloc {
namespace {

const ImuSample& sampleOf(const BufferedImu& buffered) {
  return buffered.sample;
}

}  // namespace

MeasurementHistory::MeasurementHistory(int64_t history_ns) : history_ns_(history_ns) {}

void MeasurementHistory::addImu(const BufferedImu& imu, const NavigationFilter& filter) {
  imu_.push_back(imu);
  if (started()) {
    step(imu, filter);
  }
}

void MeasurementHistory::start(const FilterSnapshot& snapshot, const NavigationFilter& filter) {
  snapshots_.clear();
  measurements_.clear();
  snapshots_.push_back(snapshot);
  replayFrom(0, filter);
}

MeasurementOutcome MeasurementHistory::add(int64_t stamp_ns, Measurement measurement,
                                           const NavigationFilter& filter) {
  if (stamp_ns <= snapshots_.front().state.stamp_ns) {
    ++counters_[static_cast<size_t>(measurement.kind())].too_late;
    return MeasurementOutcome::kTooLate;
  }
  const auto inserted = measurements_.emplace(stamp_ns, std::move(measurement));
  // The first snapshot at or after the measurement: the step to it applies the measurement.
  const auto at_or_after = std::lower_bound(snapshots_.begin(), snapshots_.end(), stamp_ns,
                                            [](const FilterSnapshot& snapshot, int64_t stamp) {
                                              return snapshot.state.stamp_ns < stamp;
                                            });
  if (at_or_after != snapshots_.end()) {
    replayFrom(static_cast<size_t>(at_or_after - snapshots_.begin()) - 1, filter);
  }
  return inserted->second.outcome.value_or(MeasurementOutcome::kPending);
}

void MeasurementHistory::replayFrom(size_t snapshot_index, const NavigationFilter& filter) {
  snapshots_.erase(snapshots_.begin() + static_cast<std::ptrdiff_t>(snapshot_index) + 1,
                   snapshots_.end());
  const int64_t from_ns = snapshots_.back().state.stamp_ns;
  auto next = std::upper_bound(
      imu_.begin(), imu_.end(), from_ns,
      [](int64_t stamp, const BufferedImu& imu) { return stamp < imu.sample.stamp_ns; });
  for (; next != imu_.end(); ++next) {
    step(*next, filter);
  }
}

void MeasurementHistory::step(const BufferedImu& imu, const NavigationFilter& filter) {
  FilterSnapshot snapshot = snapshots_.back();
  const ImuSample start = snapshot.imu;
  ImuSample current = start;
  const auto end = measurements_.upper_bound(imu.sample.stamp_ns);
  for (auto it = measurements_.upper_bound(start.stamp_ns); it != end; ++it) {
    const ImuSample at_measurement = interpolateImu(start, imu.sample, it->first);
    filter.propagate(current, at_measurement, snapshot);
    current = at_measurement;
    record(it->second, filter.apply(it->second, at_measurement, snapshot));
  }
  if (imu.sample.stamp_ns > current.stamp_ns) {
    filter.propagate(current, imu.sample, snapshot);
  }
  filter.updateZeroVelocity(imu.sample, imu.still, snapshot);
  snapshot.imu = imu.sample;
  snapshots_.push_back(std::move(snapshot));
}

void MeasurementHistory::record(Measurement& measurement, MeasurementOutcome outcome) {
  if (measurement.outcome == outcome) {
    return;
  }
  MeasurementCounters& counters = counters_[static_cast<size_t>(measurement.kind())];
  if (measurement.outcome) {
    --counterOf(counters, *measurement.outcome);
  }
  ++counterOf(counters, outcome);
  measurement.outcome = outcome;
}

std::vector<std::pair<int64_t, Measurement>> MeasurementHistory::prune() {
  const int64_t keep_from_ns = imu_.back().sample.stamp_ns - history_ns_;
  while (snapshots_.size() > 1 && snapshots_[1].state.stamp_ns <= keep_from_ns) {
    snapshots_.pop_front();
  }
  const int64_t first_ns = snapshots_.empty() ? keep_from_ns : snapshots_.front().state.stamp_ns;
  // Keep one sample at or before the first snapshot, for interpolation.
  while (imu_.size() > 1 && imu_[1].sample.stamp_ns <= first_ns) {
    imu_.pop_front();
  }
  const auto kept = measurements_.upper_bound(first_ns);
  std::vector<std::pair<int64_t, Measurement>> dropped;
  for (auto it = measurements_.begin(); it != kept; ++it) {
    dropped.emplace_back(it->first, std::move(it->second));
  }
  measurements_.erase(measurements_.begin(), kept);
  return dropped;
}

std::deque<FilterSnapshot>::const_iterator MeasurementHistory::after(int64_t stamp_ns) const {
  return std::upper_bound(snapshots_.begin(), snapshots_.end(), stamp_ns,
                          [](int64_t stamp, const FilterSnapshot& snapshot) {
                            return stamp < snapshot.state.stamp_ns;
                          });
}

const FilterSnapshot& MeasurementHistory::at(int64_t stamp_ns) const {
  const auto next = after(stamp_ns);
  return next == snapshots_.begin() ? snapshots_.front() : *std::prev(next);
}

FilterSnapshot MeasurementHistory::predict(int64_t stamp_ns, const NavigationFilter& filter) const {
  const auto next = after(stamp_ns);
  const FilterSnapshot& from = *std::prev(next);
  FilterSnapshot predicted = from;
  // Between two snapshots the next sample is known; past the last, hold its rates.
  ImuSample target =
      next != snapshots_.end() ? interpolateImu(from.imu, next->imu, stamp_ns) : from.imu;
  target.stamp_ns = stamp_ns;
  if (stamp_ns > predicted.state.stamp_ns) {
    filter.propagate(from.imu, target, predicted);
  }
  return predicted;
}

std::optional<ImuSample> MeasurementHistory::latestImu() const {
  if (imu_.empty()) {
    return std::nullopt;
  }
  return imu_.back().sample;
}

std::optional<ImuSample> MeasurementHistory::imuAt(int64_t stamp_ns) const {
  return lineloc::imuAt(imu_.begin(), imu_.end(), stamp_ns, &sampleOf);
}

std::optional<std::vector<ImuSample>> MeasurementHistory::imuOver(int64_t from_stamp_ns,
                                                                  int64_t to_stamp_ns) const {
  return lineloc::imuOver(imu_.begin(), imu_.end(), from_stamp_ns, to_stamp_ns, &sampleOf);
}

}  // namespace lineloc
