// The ground level of the model under a ground robot, whose camera height
// above the ground it stands on is known. Where the view holds the model's
// terrain (a TIN), it is the terrain's height under the robot
// (common/geometry/terrain_surface.h), so streets that slope are followed.
// Elsewhere (a model without terrain, or beyond its edge) it is the median
// over the buildings in view of each building's lowest vertex: city models
// stand every building on the terrain, and the median ignores one on a podium
// or in a dip.
#pragma once

#include <Eigen/Core>
#include <optional>

#include "backbone/map/map_tile_cache.h"
#include "common/geometry/terrain_surface.h"

namespace lineloc {

class GroundLevel {
 public:
  explicit GroundLevel(const MapView& view);

  // nullopt when the view holds no terrain under `position_world` and no faces.
  std::optional<double> at(const Eigen::Vector2d& position_world) const;

 private:
  TerrainSurface terrain_;
  std::optional<double> building_feet_median_;
};

}  // namespace lineloc
