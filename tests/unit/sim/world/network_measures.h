// Sizes of a street network for the tests to check and print: nodes of a
// degree, and the share of its length in its largest connected part.
#pragma once

#include <fmt/format.h>

#include <algorithm>
#include <string>

#include "sim/world/street_network.h"

namespace lineloc {

inline int countDegree(const StreetNetwork& network, int degree) {
  return static_cast<int>(std::count_if(network.nodes.begin(), network.nodes.end(),
                                        [&](const auto& node) { return node.degree() == degree; }));
}

// Share of the network's edge length in its largest connected part.
inline double largestComponentShare(const StreetNetwork& network) {
  const std::vector<int> component = network.components();
  double total_m = 0.0;
  double largest_m = 0.0;
  for (const StreetNetwork::Edge& edge : network.edges) {
    total_m += edge.length_m;
    largest_m += component[edge.from] == 0 ? edge.length_m : 0.0;
  }
  return largest_m / total_m;
}

inline void printSize(const std::string& name, const StreetNetwork& network) {
  fmt::print(
      "{}: {} nodes ({} junctions, {} dead ends), {} edges, largest part {:.0f} % of length\n",
      name, network.nodes.size(), network.nodes.size() - countDegree(network, 1),
      countDegree(network, 1), network.edges.size(), 100.0 * largestComponentShare(network));
}

}  // namespace lineloc
