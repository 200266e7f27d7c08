// One IMU measurement in the body frame (x forward, y left, z up): angular
// rate and specific force (acceleration minus gravity), stamped with the time
// it was measured.
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <cstdint>
#include <iterator>
#include <optional>
#include <vector>

namespace lineloc {

struct ImuSample {
  int64_t stamp_ns = 0;
  Eigen::Vector3d gyro_radps = Eigen::Vector3d::Zero();
  Eigen::Vector3d accel_mps2 = Eigen::Vector3d::Zero();
};

// Continuous-time noise densities of a MEMS IMU, as a datasheet or a Kalibr
// IMU file gives them: white noise on the rates and random walk of the biases.
struct ImuNoiseDensities {
  double gyro_noise_radps_per_sqrt_hz = 1.6968e-4;
  double accel_noise_mps2_per_sqrt_hz = 2.0e-3;
  double gyro_bias_random_walk_radps2_per_sqrt_hz = 1.9393e-5;
  double accel_bias_random_walk_mps3_per_sqrt_hz = 3.0e-3;
};

// Linear interpolation of rates and specific force at `stamp_ns` between a and b.
ImuSample interpolateImu(const ImuSample& a, const ImuSample& b, int64_t stamp_ns);

// The reading at `stamp_ns` among time-sorted elements [first, last), each
// holding its ImuSample at `sample_of(element)`: interpolated between the two
// around it, nullopt outside them.
template <typename Iterator, typename SampleOf>
std::optional<ImuSample> imuAt(Iterator first, Iterator last, int64_t stamp_ns,
                               SampleOf sample_of) {
  const auto after = std::partition_point(
      first, last, [&](const auto& element) { return sample_of(element).stamp_ns < stamp_ns; });
  if (after == last) {
    return std::nullopt;
  }
  if (sample_of(*after).stamp_ns == stamp_ns) {
    return sample_of(*after);
  }
  if (after == first) {
    return std::nullopt;
  }
  return interpolateImu(sample_of(*std::prev(after)), sample_of(*after), stamp_ns);
}

// The samples of [from_stamp_ns, to_stamp_ns] among time-sorted elements, the
// ends interpolated; nullopt when the elements do not cover the interval or it
// is empty.
template <typename Iterator, typename SampleOf>
std::optional<std::vector<ImuSample>> imuOver(Iterator first, Iterator last, int64_t from_stamp_ns,
                                              int64_t to_stamp_ns, SampleOf sample_of) {
  const std::optional<ImuSample> from = imuAt(first, last, from_stamp_ns, sample_of);
  const std::optional<ImuSample> to = imuAt(first, last, to_stamp_ns, sample_of);
  if (!(to_stamp_ns > from_stamp_ns) || !from || !to) {
    return std::nullopt;
  }
  std::vector<ImuSample> samples{*from};
  for (auto it = std::partition_point(
           first, last,
           [&](const auto& element) { return sample_of(element).stamp_ns <= from_stamp_ns; });
       it != last && sample_of(*it).stamp_ns < to_stamp_ns; ++it) {
    samples.push_back(sample_of(*it));
  }
  samples.push_back(*to);
  return samples;
}

}  // namespace lineloc
