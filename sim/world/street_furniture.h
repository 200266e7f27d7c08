// What real streets hold besides the things standing in them
// (street_clutter.h), each a straight edge no city model has: cables spanning
// the street from façade to façade, every other one with a lamp hung over its
// middle, the highest edges against the sky; a dashed lane line beside the
// route; kerbs between the pavements and the road. Each is laid along the
// route, where the occupancy map finds the façades either side of it.
//
// A cable is made of pieces at most a metre long, each an object of its own,
// so that the box around each (clutter_boxes.h) stays as thin as the cable.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <functional>
#include <vector>

#include "sim/render/scene_mesh.h"
#include "sim/world/occupancy_map.h"

namespace lineloc {

struct StreetFurnitureOptions {
  // Cables across the street per 100 m of route, at a height drawn from
  // [min_cable_height_m, max_cable_height_m] above the route's ground, where
  // a façade stands within max_cable_span_m / 2 on either side.
  double cables_per_100m = 0.0;
  double min_cable_height_m = 6.0;
  double max_cable_height_m = 8.5;
  // A bundle of cables: thinner, and one ray per pixel would miss most of
  // it beyond 15 m.
  double cable_diameter_m = 0.04;
  double max_cable_span_m = 40.0;
  // A dashed line lane_marking_offset_m left of the route (3 m painted, 6 m
  // not, 12 cm wide), where the façade on the left is at least
  // min_road_half_width_m beyond it.
  bool lane_markings = false;
  double lane_marking_offset_m = 1.75;
  // Kerbs pavement_width_m from the façades either side, where the route
  // keeps min_road_half_width_m from them.
  bool kerbs = false;
  double pavement_width_m = 1.8;
  double min_road_half_width_m = 2.0;
  uint32_t seed = 1;
};

struct StreetFurnitureCounts {
  int cables = 0;
  int lamps = 0;
  int marking_dashes = 0;
  // Metres of kerb.
  double kerb_m = 0.0;
};

// Adds the furniture to `mesh`, object ids from `first_object_id` on, each on
// the ground at `ground_height_m` of its position (m, world z).
StreetFurnitureCounts addStreetFurniture(
    const OccupancyMap& map, const std::vector<Eigen::Vector2d>& route,
    const std::function<double(const Eigen::Vector2d&)>& ground_height_m,
    const StreetFurnitureOptions& options, uint32_t first_object_id, SceneMesh& mesh);

}  // namespace lineloc
