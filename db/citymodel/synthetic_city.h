// A synthetic city for scale tests: N buildings along the four sides of square
// blocks on a street grid, each a rectangular footprint of realistic size
// (6-16 m frontage, 10-14 m deep) and height (6-24 m eaves), with a flat roof
// or a gabled LoD2 roof (30-45° pitch, ridge along the longer side), every face
// with its semantic kind. Deterministic for a given seed.
#pragma once

#include <Eigen/Core>
#include <cstdint>

#include "db/citymodel/city_model.h"

namespace lineloc::citymodel {

struct SyntheticCityOptions {
  int building_count = 1000;
  uint32_t seed = 1;
  double block_size_m = 80.0;  // built square per block
  double street_width_m = 20.0;
  double gabled_fraction = 0.5;
  int epsg = 7415;
  Eigen::Vector3d origin = {85000.0, 447000.0, 0.0};  // south-west corner of the first block
};

// Buildings are numbered "b<n>" in block order, so neighbours are near in the list.
// A flat-roofed building has 12 visible edges, a gabled one 15 (4 ground, 4
// vertical, 2 eaves, 4 gable rakes, 1 ridge); attribute "roof" says which.
CityModel generateSyntheticCity(const SyntheticCityOptions& options);

// Centre lines of the streets between blocks, for picking query positions:
// returns a point on a street, x east y north, in the model CRS.
Eigen::Vector2d randomStreetPoint(const SyntheticCityOptions& options, uint32_t draw);

}  // namespace lineloc::citymodel
