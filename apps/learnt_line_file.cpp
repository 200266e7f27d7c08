#include "apps/learnt_line_file.h"

#include <fmt/format.h>

#include <fstream>
#include <stdexcept>

#include "common/geometry/pose.h"

namespace lineloc {

void writeLearntLineFile(const std::string& path, const std::vector<LearntLineRow>& rows) {
  std::ofstream file(path);
  if (!file) {
    throw std::runtime_error(fmt::format("cannot write the learnt lines to {}", path));
  }
  file << "# x0 y0 z0 x1 y1 z1 (m, site frame) building views robots sigma0_m sigma1_m "
          "(largest standard deviation of each end across the line)\n";
  for (const LearntLineRow& row : rows) {
    file << fmt::format("{:.4f} {:.4f} {:.4f} {:.4f} {:.4f} {:.4f} {} {} {} {:.4f} {:.4f}\n",
                        row.start_world.x(), row.start_world.y(), row.start_world.z(),
                        row.end_world.x(), row.end_world.y(), row.end_world.z(), row.building,
                        row.views, row.robots, largestSigma(row.start_covariance),
                        largestSigma(row.end_covariance));
  }
  if (!file) {
    throw std::runtime_error(fmt::format("could not write all learnt lines to {}", path));
  }
}

}  // namespace lineloc
