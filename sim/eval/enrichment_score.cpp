#include "sim/eval/enrichment_score.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <unordered_map>

#include "common/geometry/line_segments.h"
#include "common/text/data_rows.h"

namespace lineloc {
namespace {

constexpr int kMinSamples = 5;

// The edges by the cells of a grid of reach_m that their boxes touch.
class EdgeGrid {
 public:
  EdgeGrid(const std::vector<FacadeEdge>& edges, double cell_m) : cell_m_(cell_m) {
    for (size_t i = 0; i < edges.size(); ++i) {
      forCells(edges[i].start.cwiseMin(edges[i].end), edges[i].start.cwiseMax(edges[i].end),
               [&](const Key& key) { cells_[key].push_back(static_cast<int>(i)); });
    }
  }

  // The edges whose cells touch the box, each once.
  std::vector<int> near(const Eigen::Vector3d& low, const Eigen::Vector3d& high) const {
    std::vector<int> found;
    forCells(low, high, [&](const Key& key) {
      if (const auto it = cells_.find(key); it != cells_.end()) {
        found.insert(found.end(), it->second.begin(), it->second.end());
      }
    });
    std::sort(found.begin(), found.end());
    found.erase(std::unique(found.begin(), found.end()), found.end());
    return found;
  }

 private:
  using Key = std::array<long long, 3>;
  struct KeyHash {
    size_t operator()(const Key& key) const {
      return static_cast<size_t>(key[0] * 73856093LL ^ key[1] * 19349663LL ^ key[2] * 83492791LL);
    }
  };

  template <typename Visit>
  void forCells(const Eigen::Vector3d& low, const Eigen::Vector3d& high, Visit visit) const {
    const auto index = [&](double value) { return std::llround(std::floor(value / cell_m_)); };
    for (long long x = index(low.x()); x <= index(high.x()); ++x) {
      for (long long y = index(low.y()); y <= index(high.y()); ++y) {
        for (long long z = index(low.z()); z <= index(high.z()); ++z) {
          visit(Key{x, y, z});
        }
      }
    }
  }

  double cell_m_;
  std::unordered_map<Key, std::vector<int>, KeyHash> cells_;
};

}  // namespace

std::vector<LearntLine> parseLearntLines(std::string_view text, const std::string& source) {
  std::vector<LearntLine> lines;
  forEachDataRow(text, [&](const std::string& row, int number) {
    std::istringstream fields(row);
    LearntLine line;
    if (!(fields >> line.start.x() >> line.start.y() >> line.start.z() >> line.end.x() >>
          line.end.y() >> line.end.z()) ||
        !line.start.allFinite() || !line.end.allFinite()) {
      throw std::runtime_error(
          fmt::format("{}:{}: expected 'x0 y0 z0 x1 y1 z1 ...' (finite numbers), got '{}'", source,
                      number, row));
    }
    lines.push_back(line);
  });
  return lines;
}

std::vector<LearntLine> readLearntLines(const std::string& path) {
  return parseLearntLines(readTextFile(path, "learnt lines"), path);
}

EnrichmentScore scoreEnrichment(const std::vector<LearntLine>& lines,
                                const std::vector<FacadeEdge>& truth,
                                const std::vector<ClutterBox>& clutter,
                                const EnrichmentScoreOptions& options) {
  EnrichmentScore score;
  score.lines = static_cast<int>(lines.size());
  const EdgeGrid grid(truth, options.reach_m);
  const Eigen::Vector3d reach = Eigen::Vector3d::Constant(options.reach_m);
  for (const LearntLine& line : lines) {
    const int samples = std::max(
        kMinSamples, static_cast<int>((line.end - line.start).norm() / options.sample_spacing_m));
    double sum = 0.0;
    double clutter_sum = 0.0;
    for (int k = 0; k < samples; ++k) {
      const Eigen::Vector3d point = line.start + (k + 0.5) / samples * (line.end - line.start);
      double nearest = std::numeric_limits<double>::infinity();
      for (const int i : grid.near(point - reach, point + reach)) {
        nearest = std::min(nearest, distanceToSegment(point, truth[i].start, truth[i].end));
      }
      sum += nearest;
      double nearest_clutter = std::numeric_limits<double>::infinity();
      for (const ClutterBox& box : clutter) {
        nearest_clutter = std::min(nearest_clutter, box.box_world.exteriorDistance(point));
      }
      clutter_sum += nearest_clutter;
    }
    score.on_clutter +=
        clutter_sum / samples <= options.clutter_margin_m && clutter_sum < sum ? 1 : 0;
    score.distances_m.push_back(sum / samples);
  }
  if (!lines.empty()) {
    std::vector<double> sorted = score.distances_m;
    std::nth_element(sorted.begin(), sorted.begin() + sorted.size() / 2, sorted.end());
    score.median_distance_m = sorted[sorted.size() / 2];
    score.within_fraction =
        static_cast<double>(std::count_if(sorted.begin(), sorted.end(),
                                          [&](double d) { return d <= options.within_m; })) /
        static_cast<double>(sorted.size());
  }
  return score;
}

}  // namespace lineloc
