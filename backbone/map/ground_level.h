// The ground level of the model near a robot, for a ground robot whose camera
// height above the ground it stands on is known: the median over the buildings
// in view of each building's lowest vertex (city models stand every building
// on the terrain; the median ignores one on a podium or in a dip).
#pragma once

#include <optional>

#include "backbone/map/map_tile_cache.h"

namespace lineloc {

// nullopt when the view holds no faces.
std::optional<double> groundLevel(const MapView& view);

}  // namespace lineloc
