#include "db/citymodel/synthetic_city.h"

#include <fmt/format.h>

#include <cmath>
#include <random>

#include "common/geometry/polygon_triangulation.h"
#include "db/citymodel/footprint_reader.h"
#include "db/citymodel/polygon_geometry.h"

namespace lineloc::citymodel {
namespace {

constexpr double kDepthMin_m = 10.0, kDepthMax_m = 14.0;
constexpr double kFrontageMin_m = 6.0, kFrontageMax_m = 16.0;
constexpr double kEaveMin_m = 6.0, kEaveMax_m = 24.0;
constexpr double kPitchMin_rad = 30.0 * M_PI / 180.0, kPitchMax_rad = 45.0 * M_PI / 180.0;

struct Rectangle {
  Eigen::Vector2d min;
  Eigen::Vector2d max;
};

// Reverses the ring when its normal points towards `inside` rather than away.
Face outward(SurfaceKind kind, std::vector<Eigen::Vector3d> ring, const Eigen::Vector3d& inside) {
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& point : ring) {
    centroid += point;
  }
  centroid /= static_cast<double>(ring.size());
  if (newellNormal(ring).dot(centroid - inside) < 0.0) {
    std::reverse(ring.begin(), ring.end());
  }
  return Face{kind, {std::move(ring)}};
}

std::vector<Face> gabledBlock(const Rectangle& footprint, double eave_m, double pitch_rad,
                              double base_z) {
  const Eigen::Vector2d extent = footprint.max - footprint.min;
  const bool ridge_along_x = extent.x() >= extent.y();
  const double length = ridge_along_x ? extent.x() : extent.y();
  const double width = ridge_along_x ? extent.y() : extent.x();
  const double ridge_m = eave_m + 0.5 * width * std::tan(pitch_rad);
  // Local (u along the ridge, v across it, z up) to the model frame.
  const auto at = [&](double u, double v, double z) {
    return ridge_along_x
               ? Eigen::Vector3d(footprint.min.x() + u, footprint.min.y() + v, base_z + z)
               : Eigen::Vector3d(footprint.min.x() + v, footprint.min.y() + u, base_z + z);
  };
  const double L = length, W = width, h = eave_m, r = ridge_m;
  const Eigen::Vector3d inside = at(0.5 * L, 0.5 * W, 0.5 * h);
  return {
      outward(SurfaceKind::kGround, {at(0, 0, 0), at(L, 0, 0), at(L, W, 0), at(0, W, 0)}, inside),
      outward(SurfaceKind::kWall, {at(0, 0, 0), at(L, 0, 0), at(L, 0, h), at(0, 0, h)}, inside),
      outward(SurfaceKind::kWall, {at(0, W, 0), at(L, W, 0), at(L, W, h), at(0, W, h)}, inside),
      outward(SurfaceKind::kWall,
              {at(0, 0, 0), at(0, W, 0), at(0, W, h), at(0, 0.5 * W, r), at(0, 0, h)}, inside),
      outward(SurfaceKind::kWall,
              {at(L, 0, 0), at(L, W, 0), at(L, W, h), at(L, 0.5 * W, r), at(L, 0, h)}, inside),
      outward(SurfaceKind::kRoof, {at(0, 0, h), at(L, 0, h), at(L, 0.5 * W, r), at(0, 0.5 * W, r)},
              inside),
      outward(SurfaceKind::kRoof, {at(0, W, h), at(L, W, h), at(L, 0.5 * W, r), at(0, 0.5 * W, r)},
              inside),
  };
}

// Footprints along the four sides of one block whose south-west corner is `corner`.
std::vector<Rectangle> blockFootprints(const Eigen::Vector2d& corner, double size,
                                       std::mt19937& random) {
  std::uniform_real_distribution<double> frontage(kFrontageMin_m, kFrontageMax_m);
  std::uniform_real_distribution<double> depth_draw(kDepthMin_m, kDepthMax_m);
  const double depth = depth_draw(random);
  std::vector<Rectangle> footprints;
  // Fills [from, to) along one axis with frontages; `make` turns a span into a rectangle.
  const auto fill = [&](double from, double to, auto make) {
    double at = from;
    while (to - at >= kFrontageMin_m) {
      const double end = std::min(to, at + frontage(random));
      // A remainder too narrow for a building joins the last one.
      const double span_end = to - end < kFrontageMin_m ? to : end;
      footprints.push_back(make(at, span_end));
      at = span_end;
    }
  };
  const Eigen::Vector2d c = corner;
  fill(0.0, size, [&](double a, double b) {
    return Rectangle{c + Eigen::Vector2d(a, 0), c + Eigen::Vector2d(b, depth)};
  });
  fill(0.0, size, [&](double a, double b) {
    return Rectangle{c + Eigen::Vector2d(a, size - depth), c + Eigen::Vector2d(b, size)};
  });
  fill(depth, size - depth, [&](double a, double b) {
    return Rectangle{c + Eigen::Vector2d(0, a), c + Eigen::Vector2d(depth, b)};
  });
  fill(depth, size - depth, [&](double a, double b) {
    return Rectangle{c + Eigen::Vector2d(size - depth, a), c + Eigen::Vector2d(size, b)};
  });
  return footprints;
}

// Expected buildings per block: two full sides and two sides shortened by the
// depth of the corner buildings, over the mean frontage.
double buildingsPerBlock(const SyntheticCityOptions& options) {
  const double mean_frontage_m = 0.5 * (kFrontageMin_m + kFrontageMax_m);
  const double mean_depth_m = 0.5 * (kDepthMin_m + kDepthMax_m);
  return (4.0 * options.block_size_m - 4.0 * mean_depth_m) / mean_frontage_m;
}

// A square grid of blocks.
int blocksPerRow(const SyntheticCityOptions& options) {
  const double blocks = options.building_count / buildingsPerBlock(options);
  return std::max(1, static_cast<int>(std::ceil(std::sqrt(blocks))));
}

}  // namespace

CityModel generateSyntheticCity(const SyntheticCityOptions& options) {
  std::mt19937 random(options.seed);
  std::uniform_real_distribution<double> eave(kEaveMin_m, kEaveMax_m);
  std::uniform_real_distribution<double> pitch(kPitchMin_rad, kPitchMax_rad);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  CityModel model;
  model.epsg = options.epsg;
  const int per_row = blocksPerRow(options);
  const double pitch_m = options.block_size_m + options.street_width_m;
  for (int block = 0; static_cast<int>(model.buildings.size()) < options.building_count; ++block) {
    const Eigen::Vector2d corner =
        options.origin.head<2>() + Eigen::Vector2d(block % per_row, block / per_row) * pitch_m;
    for (const Rectangle& footprint : blockFootprints(corner, options.block_size_m, random)) {
      if (static_cast<int>(model.buildings.size()) == options.building_count) {
        break;
      }
      const bool gabled = unit(random) < options.gabled_fraction;
      const double eave_m = eave(random);
      Building building;
      building.id = fmt::format("b{}", model.buildings.size());
      building.type = "Building";
      building.lod = gabled ? "2.2" : "1.2";
      building.attributes_json = fmt::format(R"({{"roof": "{}"}})", gabled ? "gabled" : "flat");
      building.faces = gabled ? gabledBlock(footprint, eave_m, pitch(random), options.origin.z())
                              : extrudeFootprint({{footprint.min,
                                                   {footprint.max.x(), footprint.min.y()},
                                                   footprint.max,
                                                   {footprint.min.x(), footprint.max.y()}}},
                                                 options.origin.z(), eave_m);
      model.buildings.push_back(std::move(building));
    }
  }
  return model;
}

Eigen::Vector2d randomStreetPoint(const SyntheticCityOptions& options, uint32_t draw) {
  std::mt19937 random(options.seed * 7919u + draw);
  const int per_row = blocksPerRow(options);
  // Full rows only, so the point always has blocks on both sides.
  const int full_rows = std::max(
      1, static_cast<int>(options.building_count / (per_row * buildingsPerBlock(options))) - 1);
  const double pitch_m = options.block_size_m + options.street_width_m;
  std::uniform_real_distribution<double> along(0.0, per_row * pitch_m);
  std::uniform_real_distribution<double> across(0.0, full_rows * pitch_m);
  std::uniform_int_distribution<int> street(0, std::min(per_row, full_rows) - 1);
  const double centre =
      street(random) * pitch_m + options.block_size_m + 0.5 * options.street_width_m;
  const Eigen::Vector2d offset = random() % 2 == 0 ? Eigen::Vector2d(centre, across(random))
                                                   : Eigen::Vector2d(along(random), centre);
  return options.origin.head<2>() + offset;
}

}  // namespace lineloc::citymodel
