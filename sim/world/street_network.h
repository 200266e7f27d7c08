// The street network of a city model: a graph along the centre lines of the
// free space between building footprints. Street cells of an OccupancyMap
// have at least min_clearance_m to the nearest building and buildings on two
// opposite sides within max_facade_distance_m (open land beyond the model's
// edge is not street: the model's border is where the world ends). Their
// skeleton, by Zhang-Suen thinning (T. Y. Zhang, C. Y. Suen, "A fast parallel
// algorithm for thinning digital patterns", CACM 27(3), 1984; cv::ximgproc),
// approximates the medial axis of the free space (H. Blum, "A transformation
// for extracting new descriptors of shape", 1967): skeleton pixels with three
// or more 8-neighbours are junctions, those with one dead ends, and the chains
// of pixels between them the edges. The graph is then cleaned until it stops
// changing:
//  - a spur (an edge from a junction to a dead end) shorter than the street
//    width at its junction, 2 c for the junction's clearance c, is skeleton
//    noise from a façade jog or the ragged end of the street cells: removed;
//  - two junctions joined by an edge shorter than the larger of their
//    clearances lie in one crossing: merged into one node at their mean;
//  - a node left with two edges joins them into one.
// Edge polylines are simplified by Douglas-Peucker (cv::approxPolyDP).
// Skeleton cycles without any junction (a courtyard's ring) are left out.
#pragma once

#include <Eigen/Core>
#include <utility>
#include <vector>

#include "sim/world/occupancy_map.h"

namespace lineloc {

struct StreetNetworkOptions {
  // The robot keeps at least this far from façades (m).
  double min_clearance_m = 3.0;
  // A street cell has buildings within this distance on both sides along one
  // of eight axes, 22.5 degrees apart: a square up to twice this across is
  // street, the open land beyond the model's edge is not (m).
  double max_facade_distance_m = 40.0;
  // Edge polylines deviate at most this far from the skeleton (m).
  double simplify_tolerance_m = 0.5;
};

struct StreetNetwork {
  struct Node {
    Eigen::Vector2d xy;  // world frame (m)
    // Distance to the nearest building (m).
    double clearance_m = 0.0;
    // The edges that meet here; a loop appears twice.
    std::vector<int> edges;
    int degree() const { return static_cast<int>(edges.size()); }
  };
  struct Edge {
    int from = -1;
    int to = -1;
    // World xy from node `from` to node `to`, both ends included (m).
    std::vector<Eigen::Vector2d> polyline;
    double length_m = 0.0;
  };
  std::vector<Node> nodes;
  std::vector<Edge> edges;

  // The connected component of every node, numbered from 0 by falling total
  // edge length (component 0 is the largest).
  std::vector<int> components() const;
};

StreetNetwork buildStreetNetwork(const OccupancyMap& map, const StreetNetworkOptions& options);

// Length of a polyline (m).
double polylineLength(const std::vector<Eigen::Vector2d>& points);

}  // namespace lineloc
