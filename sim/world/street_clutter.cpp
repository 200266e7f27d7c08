#include "sim/world/street_clutter.h"

#include <array>
#include <cmath>
#include <numbers>
#include <opencv2/imgproc.hpp>
#include <random>

#include "sim/world/street_route.h"

namespace lineloc {
namespace {

constexpr int kAttemptsPerObject = 60;

// Where one kind of object may stand: a band of clearance from the façades
// and a minimum spacing to every other object.
struct Placement {
  double min_clearance_m;
  double max_clearance_m;
  double spacing_m;
};

constexpr Placement kCarPlacement{2.2, 3.6, 5.0};
constexpr Placement kTreePlacement{4.0, 9.0, 6.0};
constexpr Placement kTallTreePlacement{1.5, 4.0, 8.0};
constexpr Placement kPolePlacement{2.0, 6.0, 4.0};
constexpr Placement kPedestrianPlacement{0.8, 4.0, 1.5};

Eigen::Isometry3d placeOnGround(const Eigen::Vector2d& xy, double yaw_rad, double z) {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() = Eigen::AngleAxisd(yaw_rad, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  pose.translation() = Eigen::Vector3d(xy.x(), xy.y(), z);
  return pose;
}

void addPart(SceneMesh& mesh, const Eigen::Isometry3d& T_world_object,
             const Eigen::Vector3d& centre, const Eigen::Vector3d& size, SurfaceKind kind,
             uint32_t id) {
  mesh.addBox(T_world_object * Eigen::Translation3d(centre), 0.5 * size,
              SurfaceTag{kind, id, static_cast<float>(T_world_object.translation().z()),
                         static_cast<float>(T_world_object.translation().z() + size.z())});
}

// A hatchback: body on wheels' height, glazed cabin on top; x along the car.
void addCar(SceneMesh& mesh, const Eigen::Isometry3d& T, uint32_t id) {
  addPart(mesh, T, {0.0, 0.0, 0.68}, {4.2, 1.75, 0.76}, SurfaceKind::kCarBody, id);
  addPart(mesh, T, {-0.25, 0.0, 1.33}, {2.3, 1.55, 0.54}, SurfaceKind::kCarWindow, id);
  for (const double x : {-1.35, 1.35}) {
    addPart(mesh, T, {x, 0.0, 0.3}, {0.6, 1.6, 0.6}, SurfaceKind::kTreeTrunk, id);
  }
}

// A trunk under a low-poly crown: an icosahedron whose vertices are pushed
// in and out by up to 20%.
void addTree(SceneMesh& mesh, const Eigen::Isometry3d& T, uint32_t id, double height_m,
             std::mt19937& random) {
  const double trunk_m = 0.45 * height_m;
  addPart(mesh, T, {0.0, 0.0, 0.5 * trunk_m}, {0.35, 0.35, trunk_m}, SurfaceKind::kTreeTrunk, id);
  const double radius = 0.3 * height_m;
  const Eigen::Vector3d centre = T * Eigen::Vector3d(0.0, 0.0, height_m - radius);
  const double phi = 0.5 * (1.0 + std::sqrt(5.0));
  std::array<Eigen::Vector3d, 12> vertices = {Eigen::Vector3d(-1, phi, 0),
                                              {1, phi, 0},
                                              {-1, -phi, 0},
                                              {1, -phi, 0},
                                              {0, -1, phi},
                                              {0, 1, phi},
                                              {0, -1, -phi},
                                              {0, 1, -phi},
                                              {phi, 0, -1},
                                              {phi, 0, 1},
                                              {-phi, 0, -1},
                                              {-phi, 0, 1}};
  std::uniform_real_distribution<double> jitter(0.8, 1.2);
  for (Eigen::Vector3d& vertex : vertices) {
    vertex = centre + radius * jitter(random) * vertex.normalized();
  }
  constexpr int kFaces[20][3] = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                                 {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                                 {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                                 {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
  const float base_z = static_cast<float>(T.translation().z());
  const SurfaceTag foliage{SurfaceKind::kFoliage, id, base_z,
                           base_z + static_cast<float>(height_m)};
  for (const auto& face : kFaces) {
    mesh.addTriangle(vertices[face[0]], vertices[face[1]], vertices[face[2]], foliage);
  }
}

// A lamp post: mast, arm and lamp.
void addPole(SceneMesh& mesh, const Eigen::Isometry3d& T, uint32_t id) {
  addPart(mesh, T, {0.0, 0.0, 2.25}, {0.14, 0.14, 4.5}, SurfaceKind::kPole, id);
  addPart(mesh, T, {0.5, 0.0, 4.45}, {1.0, 0.08, 0.08}, SurfaceKind::kPole, id);
  addPart(mesh, T, {0.95, 0.0, 4.35}, {0.4, 0.25, 0.15}, SurfaceKind::kPole, id);
}

void addPedestrian(SceneMesh& mesh, const Eigen::Isometry3d& T, uint32_t id, double height_m) {
  const double s = height_m / 1.75;
  addPart(mesh, T, {0.0, 0.0, 0.43 * s}, {0.25, 0.38, 0.86 * s}, SurfaceKind::kPerson, id);
  addPart(mesh, T, {0.0, 0.0, 1.17 * s}, {0.28, 0.46, 0.62 * s}, SurfaceKind::kPerson, id);
  addPart(mesh, T, {0.0, 0.0, 1.63 * s}, {0.2, 0.2, 0.24 * s}, SurfaceKind::kPerson, id + 1);
}

class ClutterPlacer {
 public:
  ClutterPlacer(const OccupancyMap& map, const std::vector<Eigen::Vector2d>& route,
                const StreetClutterOptions& options)
      : map_(map), options_(options), random_(options.seed) {
    // Distance of every cell to the route: distance transform of the drawn polyline.
    cv::Mat not_route(map.rows(), map.cols(), CV_8UC1, cv::Scalar(255));
    std::vector<cv::Point> cells;
    for (const Eigen::Vector2d& point : route) {
      cells.push_back(map.cellOf(point));
    }
    cv::polylines(not_route, cells, false, cv::Scalar(0));
    cv::distanceTransform(not_route, route_distance_m_, cv::DIST_L2, cv::DIST_MASK_PRECISE);
    route_distance_m_ *= map.cellSize();
    for (int row = 0; row < map.rows(); ++row) {
      for (int col = 0; col < map.cols(); ++col) {
        const float d = route_distance_m_.at<float>(row, col);
        if (d >= options.route_keep_out_m && d <= options.max_route_distance_m) {
          near_route_.emplace_back(col, row);
        }
      }
    }
  }

  // A free spot for an object of this placement; false when none was found.
  bool find(const Placement& placement, Eigen::Vector2d& xy) {
    if (near_route_.empty()) {
      return false;
    }
    std::uniform_int_distribution<size_t> pick(0, near_route_.size() - 1);
    std::uniform_real_distribution<double> jitter(-0.5, 0.5);
    for (int attempt = 0; attempt < kAttemptsPerObject; ++attempt) {
      const cv::Point cell = near_route_[pick(random_)];
      const double clearance = map_.clearance().at<float>(cell);
      if (clearance < placement.min_clearance_m || clearance > placement.max_clearance_m) {
        continue;
      }
      const Eigen::Vector2d candidate =
          map_.centreOf(cell) + map_.cellSize() * Eigen::Vector2d(jitter(random_), jitter(random_));
      if (isSpaced(candidate, placement.spacing_m)) {
        placed_.push_back(candidate);
        xy = candidate;
        return true;
      }
    }
    return false;
  }

  std::mt19937& random() { return random_; }

  double uniform(double low, double high) {
    return std::uniform_real_distribution<double>(low, high)(random_);
  }

 private:
  bool isSpaced(const Eigen::Vector2d& candidate, double spacing_m) const {
    for (const Eigen::Vector2d& other : placed_) {
      if ((other - candidate).norm() < spacing_m) {
        return false;
      }
    }
    return true;
  }

  const OccupancyMap& map_;
  StreetClutterOptions options_;
  std::mt19937 random_;
  cv::Mat route_distance_m_;
  std::vector<cv::Point> near_route_;
  std::vector<Eigen::Vector2d> placed_;
};

int targetCount(double per_100m, double route_length_m) {
  return static_cast<int>(std::lround(per_100m * route_length_m / 100.0));
}

}  // namespace

StreetClutterCounts addStreetClutter(
    const OccupancyMap& map, const std::vector<Eigen::Vector2d>& route,
    const std::function<double(const Eigen::Vector2d&)>& ground_height_m,
    const StreetClutterOptions& options, uint32_t first_object_id, SceneMesh& mesh) {
  ClutterPlacer placer(map, route, options);
  const double length_m = polylineLength(route);
  uint32_t id = first_object_id;
  StreetClutterCounts counts;
  Eigen::Vector2d xy;
  for (int i = 0; i < targetCount(options.cars_per_100m, length_m); ++i) {
    if (placer.find(kCarPlacement, xy)) {
      // Parked parallel to the façade: the car's x axis is perpendicular to
      // the direction away from the buildings.
      const Eigen::Vector2d away = map.awayFromBuildings(xy);
      addCar(mesh,
             placeOnGround(xy, std::atan2(away.y(), away.x()) + std::numbers::pi / 2,
                           ground_height_m(xy)),
             id++);
      ++counts.cars;
    }
  }
  for (int i = 0; i < targetCount(options.trees_per_100m, length_m); ++i) {
    if (placer.find(kTreePlacement, xy)) {
      addTree(mesh, placeOnGround(xy, 0.0, ground_height_m(xy)), id++, placer.uniform(5.0, 9.0),
              placer.random());
      ++counts.trees;
    }
  }
  for (int i = 0; i < targetCount(options.tall_trees_per_100m, length_m); ++i) {
    if (placer.find(kTallTreePlacement, xy)) {
      addTree(mesh, placeOnGround(xy, 0.0, ground_height_m(xy)), id++, placer.uniform(11.0, 16.0),
              placer.random());
      ++counts.tall_trees;
    }
  }
  for (int i = 0; i < targetCount(options.poles_per_100m, length_m); ++i) {
    if (placer.find(kPolePlacement, xy)) {
      const Eigen::Vector2d away = map.awayFromBuildings(xy);
      addPole(mesh, placeOnGround(xy, std::atan2(away.y(), away.x()), ground_height_m(xy)), id++);
      ++counts.poles;
    }
  }
  for (int i = 0; i < targetCount(options.pedestrians_per_100m, length_m); ++i) {
    if (placer.find(kPedestrianPlacement, xy)) {
      addPedestrian(
          mesh, placeOnGround(xy, placer.uniform(0.0, 2 * std::numbers::pi), ground_height_m(xy)),
          id, placer.uniform(1.55, 1.95));
      id += 2;
      ++counts.pedestrians;
    }
  }
  return counts;
}

}  // namespace lineloc
