// The text file of learnt lines that lineloc-enrich writes and
// lineloc-enrichment exports (lineloc-eval --learnt-lines reads its first six
// fields): one line per learnt line,
//   x0 y0 z0 x1 y1 z1 building views robots sigma0_m sigma1_m
// in the site frame (m), building -1 when unknown, sigma the largest standard
// deviation of each end across the line; '#' starts a comment.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <vector>

namespace lineloc {

struct LearntLineRow {
  Eigen::Vector3d start_world = Eigen::Vector3d::Zero();
  Eigen::Vector3d end_world = Eigen::Vector3d::Zero();
  int64_t building = -1;
  int views = 0;
  int robots = 0;
  Eigen::Matrix3d start_covariance = Eigen::Matrix3d::Zero();
  Eigen::Matrix3d end_covariance = Eigen::Matrix3d::Zero();
};

// Throws std::runtime_error naming the path when it cannot be written.
void writeLearntLineFile(const std::string& path, const std::vector<LearntLineRow>& rows);

}  // namespace lineloc
