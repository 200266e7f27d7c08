#include "sim/world/street_furniture.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <optional>
#include <random>

namespace lineloc {
namespace {

constexpr double kStep_m = 1.0;
constexpr double kDash_m = 3.0;
constexpr double kDashPeriod_m = 9.0;
constexpr double kMarkingWidth_m = 0.12;
constexpr double kMarkingThickness_m = 0.004;
constexpr double kKerbWidth_m = 0.15;
constexpr double kKerbHeight_m = 0.12;
// Consecutive kerb points farther apart than this (the route samples are 1 m
// apart) lie along different façades.
constexpr double kMaxKerbStep_m = 1.5;
constexpr size_t kKerbSmoothing = 3;
// Façades are looked for this far beyond the narrowest road with kerbs.
constexpr double kKerbReach_m = 20.0;
const Eigen::Vector3d kLampSize(0.5, 0.35, 0.25);
constexpr double kLampDrop_m = 0.35;

// A point of the route, its arc length and unit direction.
struct RouteSample {
  double s_m = 0.0;
  Eigen::Vector2d point = Eigen::Vector2d::Zero();
  Eigen::Vector2d direction = Eigen::Vector2d::UnitX();
};

Eigen::Vector2d leftOf(const RouteSample& sample) {
  return {-sample.direction.y(), sample.direction.x()};
}

// The route every `step_m` of arc length.
std::vector<RouteSample> sampleRoute(const std::vector<Eigen::Vector2d>& route, double step_m) {
  std::vector<RouteSample> samples;
  double next_m = 0.0;
  double start_m = 0.0;
  for (size_t i = 1; i < route.size(); ++i) {
    const Eigen::Vector2d leg = route[i] - route[i - 1];
    const double length = leg.norm();
    if (length <= 0.0) {
      continue;
    }
    for (; next_m <= start_m + length; next_m += step_m) {
      samples.push_back({next_m, route[i - 1] + (next_m - start_m) / length * leg, leg / length});
    }
    start_m += length;
  }
  return samples;
}

// Distance from `point` along `direction` to the first building cell, up to
// `range_m`.
std::optional<double> facadeDistance(const OccupancyMap& map, const Eigen::Vector2d& point,
                                     const Eigen::Vector2d& direction, double range_m) {
  for (double d = 0.0; d <= range_m; d += 0.5 * map.cellSize()) {
    const cv::Point cell = map.cellOf(point + d * direction);
    if (!map.contains(cell)) {
      return std::nullopt;
    }
    if (map.occupied().at<uint8_t>(cell) != 0) {
      return d;
    }
  }
  return std::nullopt;
}

// The box from `a` to `b` (its length along them) of the given cross-section
// (width across, horizontal; height up).
void addBeam(SceneMesh& mesh, const Eigen::Vector3d& a, const Eigen::Vector3d& b, double width_m,
             double height_m, SurfaceKind kind, uint32_t id) {
  const Eigen::Vector3d along = (b - a).normalized();
  Eigen::Vector3d across = Eigen::Vector3d::UnitZ().cross(along);
  across = across.norm() > 1e-9 ? across.normalized() : Eigen::Vector3d::UnitX();
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear().col(0) = along;
  T.linear().col(1) = across;
  T.linear().col(2) = along.cross(across);
  T.translation() = 0.5 * (a + b);
  const float base = static_cast<float>(std::min(a.z(), b.z()) - 0.5 * height_m);
  mesh.addBox(T, 0.5 * Eigen::Vector3d((b - a).norm(), width_m, height_m),
              SurfaceTag{kind, id, base, base + static_cast<float>(height_m)});
}

class FurnitureBuilder {
 public:
  FurnitureBuilder(const OccupancyMap& map,
                   const std::function<double(const Eigen::Vector2d&)>& ground_height_m,
                   const StreetFurnitureOptions& options, uint32_t first_object_id, SceneMesh& mesh)
      : map_(map),
        ground_height_m_(ground_height_m),
        options_(options),
        id_(first_object_id),
        mesh_(mesh),
        random_(options.seed) {}

  // A cable across the street at `sample`, every other one with a lamp under
  // its middle.
  void addCable(const RouteSample& sample) {
    const Eigen::Vector2d left = leftOf(sample);
    const double reach_m = 0.5 * options_.max_cable_span_m;
    const std::optional<double> to_left = facadeDistance(map_, sample.point, left, reach_m);
    const std::optional<double> to_right = facadeDistance(map_, sample.point, -left, reach_m);
    if (!to_left || !to_right) {
      return;
    }
    const double z = ground_height_m_(sample.point) +
                     std::uniform_real_distribution<double>(options_.min_cable_height_m,
                                                            options_.max_cable_height_m)(random_);
    const Eigen::Vector2d a = sample.point + *to_left * left;
    const Eigen::Vector2d b = sample.point - *to_right * left;
    const Eigen::Vector3d start(a.x(), a.y(), z);
    const Eigen::Vector3d end(b.x(), b.y(), z);
    const int pieces = std::max(1, static_cast<int>(std::ceil((end - start).norm() / kStep_m)));
    for (int i = 0; i < pieces; ++i) {
      addBeam(mesh_, start + (end - start) * i / pieces, start + (end - start) * (i + 1) / pieces,
              options_.cable_diameter_m, options_.cable_diameter_m, SurfaceKind::kCable, id_++);
    }
    if (counts_.cables++ % 2 == 0) {
      const Eigen::Vector3d middle = 0.5 * (start + end);
      const Eigen::Vector3d lamp_top = middle - Eigen::Vector3d(0.0, 0.0, kLampDrop_m);
      addBeam(mesh_, middle, lamp_top, 0.03, 0.03, SurfaceKind::kPole, id_);
      Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
      T.linear() = Eigen::AngleAxisd(std::atan2(sample.direction.y(), sample.direction.x()),
                                     Eigen::Vector3d::UnitZ())
                       .toRotationMatrix();
      T.translation() = lamp_top - Eigen::Vector3d(0.0, 0.0, 0.5 * kLampSize.z());
      const float base = static_cast<float>(T.translation().z() - 0.5 * kLampSize.z());
      mesh_.addBox(
          T, 0.5 * kLampSize,
          SurfaceTag{SurfaceKind::kPole, id_++, base, base + static_cast<float>(kLampSize.z())});
      ++counts_.lamps;
    }
  }

  // The piece of a dash of the lane line at `sample`, where it is painted.
  void addMarking(const RouteSample& sample) {
    if (std::fmod(sample.s_m, kDashPeriod_m) >= kDash_m) {
      return;
    }
    const Eigen::Vector2d left = leftOf(sample);
    const std::optional<double> to_left = facadeDistance(
        map_, sample.point, left, options_.lane_marking_offset_m + options_.min_road_half_width_m);
    if (to_left) {
      return;
    }
    const Eigen::Vector2d centre = sample.point + options_.lane_marking_offset_m * left;
    addGroundBeam(centre, sample.direction, kMarkingWidth_m, kMarkingThickness_m,
                  SurfaceKind::kRoadMarking);
    counts_.marking_dashes += std::fmod(sample.s_m, kDashPeriod_m) < kStep_m ? 1 : 0;
  }

  // A metre of kerb on either side at `sample`, where the road is wide enough.
  // The kerbs either side of the route, each along its façade: at each
  // sample, pavement_width_m short of the façade, the façade's distance
  // averaged over the samples within kKerbSmoothing either side that see the
  // same façade (within kMaxKerbStep_m), as the occupancy map places it only
  // to a cell; none across a jump (a junction, an alley), where the façade
  // changes.
  void addKerbs(const std::vector<RouteSample>& samples) {
    const double min_distance_m = options_.pavement_width_m + options_.min_road_half_width_m;
    for (const double sign : {1.0, -1.0}) {
      std::vector<std::optional<double>> facade(samples.size());
      for (size_t i = 0; i < samples.size(); ++i) {
        facade[i] = facadeDistance(map_, samples[i].point, sign * leftOf(samples[i]),
                                   min_distance_m + kKerbReach_m);
      }
      std::optional<Eigen::Vector2d> last;
      for (size_t i = 0; i < samples.size(); ++i) {
        std::optional<Eigen::Vector2d> kerb;
        if (facade[i] && *facade[i] >= min_distance_m) {
          double sum_m = 0.0;
          int count = 0;
          for (size_t j = i > kKerbSmoothing ? i - kKerbSmoothing : 0;
               j < std::min(samples.size(), i + kKerbSmoothing + 1); ++j) {
            if (facade[j] && std::abs(*facade[j] - *facade[i]) <= kMaxKerbStep_m) {
              sum_m += *facade[j];
              ++count;
            }
          }
          kerb = samples[i].point +
                 (sum_m / count - options_.pavement_width_m) * sign * leftOf(samples[i]);
        }
        if (kerb && last && (*kerb - *last).norm() <= kMaxKerbStep_m) {
          const double z = ground_height_m_(0.5 * (*kerb + *last)) + 0.5 * kKerbHeight_m;
          addBeam(mesh_, Eigen::Vector3d(last->x(), last->y(), z),
                  Eigen::Vector3d(kerb->x(), kerb->y(), z), kKerbWidth_m, kKerbHeight_m,
                  SurfaceKind::kKerb, id_++);
          counts_.kerb_m += (*kerb - *last).norm();
        }
        last = kerb;
      }
    }
  }

  const StreetFurnitureCounts& counts() const { return counts_; }

 private:
  // A metre-long box along `direction` centred on `centre`, standing on the ground.
  void addGroundBeam(const Eigen::Vector2d& centre, const Eigen::Vector2d& direction,
                     double width_m, double height_m, SurfaceKind kind) {
    const double z = ground_height_m_(centre) + 0.5 * height_m;
    const Eigen::Vector2d half = 0.5 * kStep_m * direction;
    addBeam(mesh_, Eigen::Vector3d(centre.x() - half.x(), centre.y() - half.y(), z),
            Eigen::Vector3d(centre.x() + half.x(), centre.y() + half.y(), z), width_m, height_m,
            kind, id_++);
  }

  const OccupancyMap& map_;
  const std::function<double(const Eigen::Vector2d&)>& ground_height_m_;
  const StreetFurnitureOptions& options_;
  uint32_t id_;
  SceneMesh& mesh_;
  std::mt19937 random_;
  StreetFurnitureCounts counts_;
};

}  // namespace

StreetFurnitureCounts addStreetFurniture(
    const OccupancyMap& map, const std::vector<Eigen::Vector2d>& route,
    const std::function<double(const Eigen::Vector2d&)>& ground_height_m,
    const StreetFurnitureOptions& options, uint32_t first_object_id, SceneMesh& mesh) {
  FurnitureBuilder builder(map, ground_height_m, options, first_object_id, mesh);
  const std::vector<RouteSample> samples = sampleRoute(route, kStep_m);
  if (options.cables_per_100m > 0.0) {
    const double spacing_m = 100.0 / options.cables_per_100m;
    for (double s = 0.5 * spacing_m; !samples.empty() && s <= samples.back().s_m; s += spacing_m) {
      builder.addCable(samples[static_cast<size_t>(s / kStep_m)]);
    }
  }
  for (const RouteSample& sample : samples) {
    if (options.lane_markings) {
      builder.addMarking(sample);
    }
  }
  if (options.kerbs) {
    builder.addKerbs(samples);
  }
  return builder.counts();
}

}  // namespace lineloc
