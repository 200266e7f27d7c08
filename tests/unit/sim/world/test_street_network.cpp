#include <gtest/gtest.h>

#include <algorithm>

#include "sim/world/street_network.h"
#include "tests/unit/sim/world/box_city.h"
#include "tests/unit/sim/world/network_measures.h"
#include "tests/unit/sim/world/shared_city.h"
#include "tests/unit/sim/world/street_layouts.h"

namespace lineloc {
namespace {

TEST(StreetNetwork, GridCityHasFourWayJunctionsAtTheCrossingsAndBlockLongEdges) {
  // 4 x 4 blocks, 14 m streets: three streets each way cross at x, y in
  // {47, 101, 155}, each running out into open land at both ends.
  constexpr double kStreet_m = 14.0;
  constexpr double kPitch_m = kBoxCityBlock_m + kStreet_m;
  const OccupancyMap map(makeBoxCity(4, kStreet_m), 0.5);
  const StreetNetworkOptions options;
  const StreetNetwork network = buildStreetNetwork(map, options);
  printSize("grid city", network);
  EXPECT_EQ(countDegree(network, 4), 9);
  EXPECT_EQ(countDegree(network, 1), 12);
  EXPECT_EQ(network.nodes.size(), 21u);
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      const Eigen::Vector2d crossing(kBoxCityBlock_m + 0.5 * kStreet_m + i * kPitch_m,
                                     kBoxCityBlock_m + 0.5 * kStreet_m + j * kPitch_m);
      const auto nearest = std::min_element(
          network.nodes.begin(), network.nodes.end(), [&](const auto& a, const auto& b) {
            return (a.xy - crossing).norm() < (b.xy - crossing).norm();
          });
      EXPECT_LT((nearest->xy - crossing).norm(), 1.0) << "crossing " << crossing.transpose();
      EXPECT_EQ(nearest->degree(), 4) << "crossing " << crossing.transpose();
    }
  }
  int block_edges = 0;
  for (const StreetNetwork::Edge& edge : network.edges) {
    if (network.nodes[edge.from].degree() == 4 && network.nodes[edge.to].degree() == 4) {
      ++block_edges;
      EXPECT_NEAR(edge.length_m, kPitch_m, 1.0);
    }
    EXPECT_NEAR(edge.length_m, polylineLength(edge.polyline), 1e-9);
    EXPECT_EQ(edge.polyline.front(), network.nodes[edge.from].xy);
    EXPECT_EQ(edge.polyline.back(), network.nodes[edge.to].xy);
    // On the centre line of the street: 7 m from the façades, to within the
    // simplification and a cell.
    for (const Eigen::Vector2d& xy : edge.polyline) {
      EXPECT_GE(map.clearanceAt(xy), 0.5 * kStreet_m - options.simplify_tolerance_m - 0.5);
    }
  }
  EXPECT_EQ(block_edges, 12);
  EXPECT_EQ(largestComponentShare(network), 1.0);
}

TEST(StreetNetwork, ACulDeSacEndsInADeadEndBeforeItsClosingBuilding) {
  const OccupancyMap map(makeCulDeSacCity(), 0.5);
  const StreetNetwork network = buildStreetNetwork(map, StreetNetworkOptions{});
  printSize("cul-de-sac", network);
  // The streets; the other parts are the inner corners of the buildings.
  const std::vector<int> component = network.components();
  std::vector<StreetNetwork::Node> streets;
  for (size_t n = 0; n < network.nodes.size(); ++n) {
    if (component[n] == 0) {
      streets.push_back(network.nodes[n]);
    }
  }
  ASSERT_EQ(streets.size(), 4u);
  const auto junction = std::find_if(streets.begin(), streets.end(),
                                     [](const auto& node) { return node.degree() == 3; });
  ASSERT_NE(junction, streets.end());
  EXPECT_LT((junction->xy - Eigen::Vector2d(kCulDeSacX_m, 0.0)).norm(), 1.5);
  const auto cul_de_sac_end =
      std::max_element(streets.begin(), streets.end(),
                       [](const auto& a, const auto& b) { return a.xy.y() < b.xy.y(); });
  EXPECT_EQ(cul_de_sac_end->degree(), 1);
  EXPECT_NEAR(cul_de_sac_end->xy.x(), kCulDeSacX_m, 0.5);
  // Within the street's half width of the closing façade: the skeleton ends
  // where the cells with 3 m clearance do.
  EXPECT_GT(cul_de_sac_end->xy.y(), kCulDeSacEndY_m - 7.5);
  EXPECT_LT(cul_de_sac_end->xy.y(), kCulDeSacEndY_m - 3.0);
}

TEST(StreetNetwork, NoStreetWhereTheClearanceIsTooSmall) {
  // 3 m streets plus 1 m gaps: at most 2 m to a façade, 2.9 m at crossings.
  const OccupancyMap map(makeBoxCity(2, 3.0), 0.5, 0.0);
  EXPECT_TRUE(buildStreetNetwork(map, StreetNetworkOptions{}).edges.empty());
}

TEST(StreetNetwork, DelftHasItsStreetBetweenTwoDeadEnds) {
  // The street between the two blocks, about 100 m of it between façades;
  // the other parts are courtyards and corners between buildings.
  const OccupancyMap map = bundledDelftMap();
  const StreetNetwork network = buildStreetNetwork(map, StreetNetworkOptions{});
  printSize("Delft", network);
  const std::vector<int> component = network.components();
  ASSERT_FALSE(network.edges.empty());
  double largest_m = 0.0;
  int dead_ends = 0;
  for (size_t n = 0; n < network.nodes.size(); ++n) {
    dead_ends += component[n] == 0 && network.nodes[n].degree() == 1;
  }
  for (const StreetNetwork::Edge& edge : network.edges) {
    largest_m += component[edge.from] == 0 ? edge.length_m : 0.0;
  }
  EXPECT_EQ(dead_ends, 2);
  EXPECT_GT(largest_m, 90.0);
}

}  // namespace
}  // namespace lineloc
