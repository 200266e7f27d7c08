// A drive through the streets: a polyline through the free space along
// building footprints, from a random start along the centre of the streets to
// random goals until it is long enough. Goals lie on streets: façades on two
// opposite sides, not the open land around the edge of a city model. The robot
// drives within max_facade_distance_m of the buildings, onwards (goals ahead),
// and of the drives planned takes the first whose legs all keep façades in the
// camera's view as it looks along the way: a drive looking out of the
// modelled area sees nothing the model holds (a city model is a tile of a
// city; beyond its edge the simulated world is empty). Where no leg onwards
// keeps them in view (a street that ends in open land) it turns back on a
// half circle and drives the other way. Each leg is an A*
// search on the occupancy grid with step cost length (1 + w / min(c, c_max))
// for clearance c, which keeps the route on the centre line of streets up to
// 2 c_max wide and c_max from the façades of wider ones; the cells are then
// simplified to waypoints (Douglas-Peucker, cv::approxPolyDP).
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "sim/world/occupancy_map.h"

namespace lineloc {

struct StreetRouteOptions {
  // Total length to drive (m).
  double length_m = 120.0;
  // The robot keeps at least this far from façades (m).
  double min_clearance_m = 3.0;
  // A street cell has buildings within this distance on both sides along one
  // of eight axes, 22.5 degrees apart; the robot drives no further than this
  // from the nearest building (m).
  double max_facade_distance_m = 20.0;
  // Weight w of the clearance term in the step cost (m).
  double centre_weight_m = 6.0;
  // Clearance c_max beyond which the step cost is flat (m).
  double max_centre_clearance_m = 8.0;
  // Looking along each leg, the camera sees façades over at least this share
  // of a field of view view_half_angle_deg either side, within view_range_m;
  // the drive whose least share is largest is taken when none does.
  double min_facades_in_view = 0.5;
  double view_half_angle_deg = 30.0;
  double view_range_m = 50.0;
  // Turning back, the robot keeps at least this far from façades (m): a turn
  // looks across the street, not along it.
  double min_turn_clearance_m = 1.5;
  // Goals are at least this far apart in a straight line (m).
  double min_leg_m = 30.0;
  // Waypoints deviate at most this far from the searched path (m).
  double simplify_tolerance_m = 0.75;
  // At most this many legs (goal to goal searches).
  int max_legs = 64;
  uint32_t seed = 1;
};

enum class RouteStatus { kOk, kNoStreets, kTooShort };

struct StreetRoute {
  RouteStatus status = RouteStatus::kNoStreets;
  // xy waypoints in the world frame; the first is the start.
  std::vector<Eigen::Vector2d> waypoints;
  double length_m = 0.0;
};

// kNoStreets: no street cell (clearance and façades on both sides). kTooShort: the street
// network reachable from the start is too small for length_m (the waypoints
// hold the longest route found).
StreetRoute planStreetRoute(const OccupancyMap& map, const StreetRouteOptions& options);

// Length of a polyline (m).
double polylineLength(const std::vector<Eigen::Vector2d>& points);

}  // namespace lineloc
