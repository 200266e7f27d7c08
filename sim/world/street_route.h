// A drive through the streets of a StreetNetwork: from a random point of a
// random edge of its largest connected part (chosen with probability
// proportional to length), heading either way along it, along the edges'
// centre lines until it is long enough. At a junction the robot takes one of
// the other edges there, edge e with probability proportional to
// 1 / (1 + n_e)^2 for the n_e times it has entered e, so a drive spreads over
// the streets it can reach before it repeats one. It turns back only at a
// dead end (a node with one edge): on a half circle after a diagonal to the
// side (a spline through a reversal would cusp), where the turn keeps
// min_turn_clearance_m from the buildings, as near as it fits to the last
// point on the way to the dead end from which the camera, looking along the
// street, still sees façades over min_facades_in_view of its field of view. A
// street that runs out of the modelled area (a city model is a tile of a
// city; beyond its edge the simulated world is empty) is turned in about
// where the camera would start to look out of it; one closed by a building,
// at its end.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "sim/world/occupancy_map.h"
#include "sim/world/street_network.h"

namespace lineloc {

struct StreetRouteOptions {
  // Total length to drive (m).
  double length_m = 120.0;
  // Share of the rays fanned view_half_angle_deg either side of the street's
  // direction that hit a building within view_range_m: where it falls below
  // min_facades_in_view on the way to a dead end, the robot turns back.
  double min_facades_in_view = 0.5;
  double view_half_angle_deg = 30.0;
  double view_range_m = 50.0;
  // Turning back, the robot keeps at least this far from façades (m): a turn
  // looks across the street, not along it.
  double min_turn_clearance_m = 1.5;
  uint32_t seed = 1;
};

enum class RouteStatus { kOk, kNoStreets, kTooShort };

struct StreetRoute {
  RouteStatus status = RouteStatus::kNoStreets;
  // xy waypoints in the world frame; the first is the start.
  std::vector<Eigen::Vector2d> waypoints;
  double length_m = 0.0;
  // The network's edges in the order driven; an edge that follows itself was
  // turned back on at a dead end.
  std::vector<int> edges;
};

// kNoStreets: the network has no edge the robot can drive and turn on.
// kTooShort: the drive came to a junction with no way on that it can turn
// back from (the waypoints hold the drive so far).
StreetRoute planStreetRoute(const StreetNetwork& network, const OccupancyMap& map,
                            const StreetRouteOptions& options);

}  // namespace lineloc
