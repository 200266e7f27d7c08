// Things in the street that the city model does not hold and the matcher must
// learn to ignore: parked cars along the façades, trees, lamp posts and
// pedestrians, placed beside a route (never on it) by rejection sampling on
// the occupancy map's clearance, and added to the scene as simple solids.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <functional>
#include <vector>

#include "sim/render/scene_mesh.h"
#include "sim/world/occupancy_map.h"

namespace lineloc {

struct StreetClutterOptions {
  // Objects per 100 m of route.
  double cars_per_100m = 6.0;
  double trees_per_100m = 3.0;
  // Trees 11-16 m tall within 1.5-4 m of a façade, their crowns over its
  // roof line, as real streets have and city models do not.
  double tall_trees_per_100m = 0.0;
  double poles_per_100m = 4.0;
  double pedestrians_per_100m = 4.0;
  // Nothing stands closer than this to the route (m).
  double route_keep_out_m = 2.0;
  // Nothing stands farther than this from the route (m).
  double max_route_distance_m = 15.0;
  uint32_t seed = 1;
};

struct StreetClutterCounts {
  int cars = 0;
  int trees = 0;
  int tall_trees = 0;
  int poles = 0;
  int pedestrians = 0;
};

// Adds the clutter to `mesh` (object ids from `first_object_id` on), each
// thing standing on the ground at `ground_height_m` of its position (m, world
// z), and says how many of each kind found room.
StreetClutterCounts addStreetClutter(
    const OccupancyMap& map, const std::vector<Eigen::Vector2d>& route,
    const std::function<double(const Eigen::Vector2d&)>& ground_height_m,
    const StreetClutterOptions& options, uint32_t first_object_id, SceneMesh& mesh);

}  // namespace lineloc
