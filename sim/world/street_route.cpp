#include "sim/world/street_route.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <random>

namespace lineloc {
namespace {

constexpr int kViewRays = 31;
// Radii of the half circles the robot turns back on, widest first (m); the
// route's spline (RouteTrajectory) rounds them tighter still.
constexpr double kTurnRadii_m[] = {3.0, 2.0};
// Step of the search for a turn back along the way to a dead end, and of the
// clearance check along a turn (m).
constexpr double kTurnSearchStep_m = 0.5;
constexpr double kTurnCheckStep_m = 0.25;
// The direction of a street at a point is taken over this far either side (m).
constexpr double kDirectionSpan_m = 2.0;
constexpr int kStartAttempts = 100;

// An edge driven one way: forward from its `from` node to its `to` node, or
// backward.
struct Way {
  int edge = -1;
  bool forward = true;
};

// The polyline of `way` in its direction of travel.
std::vector<Eigen::Vector2d> polylineOf(const StreetNetwork& network, const Way& way) {
  std::vector<Eigen::Vector2d> polyline = network.edges[way.edge].polyline;
  if (!way.forward) {
    std::reverse(polyline.begin(), polyline.end());
  }
  return polyline;
}

int endNode(const StreetNetwork& network, const Way& way) {
  const StreetNetwork::Edge& edge = network.edges[way.edge];
  return way.forward ? edge.to : edge.from;
}

// The point `distance_m` along a polyline (clamped to its ends).
Eigen::Vector2d pointAlong(const std::vector<Eigen::Vector2d>& polyline, double distance_m) {
  for (size_t i = 1; i < polyline.size(); ++i) {
    const double length = (polyline[i] - polyline[i - 1]).norm();
    if (distance_m <= length) {
      return polyline[i - 1] + std::max(distance_m, 0.0) / length * (polyline[i] - polyline[i - 1]);
    }
    distance_m -= length;
  }
  return polyline.back();
}

// The points of a polyline from `from_m` to `to_m` along it, both ends
// included.
std::vector<Eigen::Vector2d> stretchOf(const std::vector<Eigen::Vector2d>& polyline, double from_m,
                                       double to_m) {
  std::vector<Eigen::Vector2d> stretch{pointAlong(polyline, from_m)};
  double at_m = 0.0;
  for (size_t i = 1; i < polyline.size(); ++i) {
    at_m += (polyline[i] - polyline[i - 1]).norm();
    if (at_m > from_m && at_m < to_m) {
      stretch.push_back(polyline[i]);
    }
  }
  stretch.push_back(pointAlong(polyline, to_m));
  return stretch;
}

// Share of the rays fanned view_half_angle_deg either side of `direction`
// from `xy` that hit a building within view_range_m.
double facadeShareAhead(const OccupancyMap& map, const Eigen::Vector2d& xy,
                        const Eigen::Vector2d& direction, const StreetRouteOptions& options) {
  const double heading_rad = std::atan2(direction.y(), direction.x());
  const double half_fov_rad = options.view_half_angle_deg * M_PI / 180.0;
  int hits = 0;
  for (int ray = 0; ray < kViewRays; ++ray) {
    const double angle = heading_rad + half_fov_rad * (2.0 * ray / (kViewRays - 1) - 1.0);
    hits += map.buildingAlong(map.cellOf(xy), Eigen::Vector2d(std::cos(angle), std::sin(angle)),
                              options.view_range_m);
  }
  return static_cast<double>(hits) / kViewRays;
}

// The turn back from `start` heading along the unit `direction`: a diagonal
// to the side `side` (+1 left, -1 right) onto a half circle of radius_m
// centred radius_m ahead of `start`, which ends radius_m to the other side of
// the way it came (the turn spans 2 radius_m across the street), then back
// onto `start`. Its points after `start`; none when a point along it lies
// nearer than min_turn_clearance_m to a building.
std::vector<Eigen::Vector2d> turnLoop(const OccupancyMap& map, const Eigen::Vector2d& start,
                                      const Eigen::Vector2d& direction, int side, double radius_m,
                                      const StreetRouteOptions& options) {
  const Eigen::Vector2d aside = side * Eigen::Vector2d(-direction.y(), direction.x());
  const Eigen::Vector2d centre = start + radius_m * direction;
  // Half circles of radius r are pi r long; diagonals sqrt(2) r.
  const int arc_steps = static_cast<int>(std::ceil(M_PI * radius_m / kTurnCheckStep_m));
  const int diagonal_steps =
      static_cast<int>(std::ceil(std::sqrt(2.0) * radius_m / kTurnCheckStep_m));
  std::vector<Eigen::Vector2d> checked;
  for (int step = 1; step <= diagonal_steps; ++step) {
    checked.push_back(start + (radius_m * step / diagonal_steps) * (direction + aside));
  }
  for (int step = 1; step <= arc_steps; ++step) {
    const double turned = M_PI * step / arc_steps;
    checked.push_back(centre +
                      radius_m * (std::cos(turned) * aside + std::sin(turned) * direction));
  }
  for (int step = 1; step <= diagonal_steps; ++step) {
    checked.push_back(centre - radius_m * aside -
                      (radius_m * step / diagonal_steps) * (direction + aside));
  }
  for (const Eigen::Vector2d& xy : checked) {
    if (map.clearanceAt(xy) < options.min_turn_clearance_m) {
      return {};
    }
  }
  // The waypoints: the arc every eighth of a half circle.
  std::vector<Eigen::Vector2d> loop;
  constexpr int kArcWaypoints = 8;
  for (int step = 0; step <= kArcWaypoints; ++step) {
    const double turned = M_PI * step / kArcWaypoints;
    loop.push_back(centre + radius_m * (std::cos(turned) * aside + std::sin(turned) * direction));
  }
  loop.push_back(start);
  return loop;
}

// Where the robot turns back on the way to a dead end: at at_m along the way,
// on `loop` (which ends where it started).
struct TurnBack {
  double at_m = 0.0;
  std::vector<Eigen::Vector2d> loop;
};

// The turn back on the way to a dead end: at the point nearest to the last
// from which the camera, looking along the way, sees min_facades_in_view (the
// dead end itself when it sees them nowhere) where a turn fits; none when no
// turn fits.
std::optional<TurnBack> findTurnBack(const StreetNetwork& network, const OccupancyMap& map,
                                     const Way& way, const StreetRouteOptions& options) {
  const std::vector<Eigen::Vector2d> polyline = polylineOf(network, way);
  const double length_m = network.edges[way.edge].length_m;
  std::vector<TurnBack> fitting;
  std::optional<double> last_in_view_m;
  for (double at_m = 0.0; at_m <= length_m; at_m += kTurnSearchStep_m) {
    const Eigen::Vector2d xy = pointAlong(polyline, at_m);
    const Eigen::Vector2d direction = (pointAlong(polyline, at_m + kDirectionSpan_m) -
                                       pointAlong(polyline, at_m - kDirectionSpan_m))
                                          .normalized();
    if (facadeShareAhead(map, xy, direction, options) >= options.min_facades_in_view) {
      last_in_view_m = at_m;
    }
    std::vector<Eigen::Vector2d> loop;
    for (const double radius_m : kTurnRadii_m) {
      for (const int side : {1, -1}) {
        if (loop.empty()) {
          loop = turnLoop(map, xy, direction, side, radius_m, options);
        }
      }
    }
    if (!loop.empty()) {
      fitting.push_back({at_m, std::move(loop)});
    }
  }
  if (fitting.empty()) {
    return std::nullopt;
  }
  const double wanted_m = last_in_view_m.value_or(length_m);
  return *std::min_element(fitting.begin(), fitting.end(), [&](const auto& a, const auto& b) {
    return std::abs(a.at_m - wanted_m) < std::abs(b.at_m - wanted_m);
  });
}

class Drive {
 public:
  Drive(const StreetNetwork& network, const OccupancyMap& map, const StreetRouteOptions& options)
      : network_(network),
        map_(map),
        options_(options),
        random_(options.seed),
        entered_(network.edges.size(), 0) {}

  StreetRoute plan() {
    StreetRoute route;
    std::optional<Position> position = start();
    if (!position) {
      return route;
    }
    route.status = RouteStatus::kOk;
    route.waypoints.push_back(pointAlong(polylineOf(network_, position->way), position->at_m));
    route.edges.push_back(position->way.edge);
    while (polylineLength(route.waypoints) < options_.length_m) {
      const Way way = position->way;
      const std::vector<Eigen::Vector2d> polyline = polylineOf(network_, way);
      const int node = endNode(network_, way);
      if (network_.nodes[node].degree() == 1) {
        const TurnBack& turn = *turnBack(way);
        append(stretchOf(polyline, position->at_m, turn.at_m), route.waypoints);
        append(turn.loop, route.waypoints);
        position =
            Position{{way.edge, !way.forward}, network_.edges[way.edge].length_m - turn.at_m};
      } else {
        append(stretchOf(polyline, position->at_m, network_.edges[way.edge].length_m),
               route.waypoints);
        const std::optional<Way> next = nextWay(way, node);
        if (!next) {
          route.status = RouteStatus::kTooShort;
          break;
        }
        ++entered_[next->edge];
        position = Position{*next, 0.0};
      }
      route.edges.push_back(position->way.edge);
    }
    route.waypoints = truncate(route.waypoints, options_.length_m);
    route.length_m = polylineLength(route.waypoints);
    return route;
  }

 private:
  struct Position {
    Way way;
    double at_m = 0.0;  // along the way
  };

  // The turn back before the dead end `way` leads to (memoised).
  const std::optional<TurnBack>& turnBack(const Way& way) {
    const auto key = std::make_pair(way.edge, way.forward);
    auto found = turns_.find(key);
    if (found == turns_.end()) {
      found = turns_.emplace(key, findTurnBack(network_, map_, way, options_)).first;
    }
    return found->second;
  }

  // The stretch of `way` the robot can drive, from where it turns back before
  // a dead end behind it to where it turns back before a dead end ahead; none
  // when a turn does not fit or the turns overlap.
  std::optional<std::pair<double, double>> drivable(const Way& way) {
    const double length_m = network_.edges[way.edge].length_m;
    std::pair<double, double> stretch{0.0, length_m};
    if (network_.nodes[endNode(network_, way)].degree() == 1) {
      const std::optional<TurnBack>& ahead = turnBack(way);
      if (!ahead) {
        return std::nullopt;
      }
      stretch.second = ahead->at_m;
    }
    const Way back{way.edge, !way.forward};
    if (network_.nodes[endNode(network_, back)].degree() == 1) {
      const std::optional<TurnBack>& behind = turnBack(back);
      if (!behind) {
        return std::nullopt;
      }
      stretch.first = length_m - behind->at_m;
    }
    if (stretch.first >= stretch.second) {
      return std::nullopt;
    }
    return stretch;
  }

  // A random point of a random edge of the largest connected part, edges
  // drawn in proportion to their length, heading either way.
  std::optional<Position> start() {
    if (network_.edges.empty()) {
      return std::nullopt;
    }
    const std::vector<int> component = network_.components();
    std::vector<double> weights;
    for (const StreetNetwork::Edge& edge : network_.edges) {
      weights.push_back(component[edge.from] == 0 ? edge.length_m : 0.0);
    }
    std::discrete_distribution<int> pick_edge(weights.begin(), weights.end());
    for (int attempt = 0; attempt < kStartAttempts; ++attempt) {
      const Way way{pick_edge(random_), std::bernoulli_distribution(0.5)(random_)};
      if (const auto stretch = drivable(way)) {
        ++entered_[way.edge];
        return Position{
            way, std::uniform_real_distribution<double>(stretch->first, stretch->second)(random_)};
      }
    }
    return std::nullopt;
  }

  // The way on from `node`, reached along `arrived`: any other edge end
  // there that the robot can drive, drawn with weight 1 / (1 + n)^2 for the n
  // times its edge was entered; none when there is no such end.
  std::optional<Way> nextWay(const Way& arrived, int node) {
    const std::vector<int>& at_node = network_.nodes[node].edges;
    std::vector<Way> ways;
    std::vector<double> weights;
    for (auto e = at_node.begin(); e != at_node.end(); ++e) {
      // A loop is listed twice: left forward at its first entry, backward at its second.
      const bool forward =
          network_.edges[*e].from == node && std::find(at_node.begin(), e, *e) == e;
      const Way way{*e, forward};
      if ((way.edge == arrived.edge && way.forward != arrived.forward) || !drivable(way)) {
        continue;
      }
      ways.push_back(way);
      weights.push_back(1.0 / std::pow(1.0 + entered_[*e], 2));
    }
    if (ways.empty()) {
      return std::nullopt;
    }
    return ways[std::discrete_distribution<size_t>(weights.begin(), weights.end())(random_)];
  }

  // Appends `points` to `waypoints`, leaving out a first point that repeats
  // the last waypoint.
  static void append(const std::vector<Eigen::Vector2d>& points,
                     std::vector<Eigen::Vector2d>& waypoints) {
    for (const Eigen::Vector2d& point : points) {
      if (waypoints.empty() || (point - waypoints.back()).norm() > 1e-6) {
        waypoints.push_back(point);
      }
    }
  }

  // The first length_m of a polyline.
  static std::vector<Eigen::Vector2d> truncate(const std::vector<Eigen::Vector2d>& polyline,
                                               double length_m) {
    return polylineLength(polyline) <= length_m ? polyline : stretchOf(polyline, 0.0, length_m);
  }

  const StreetNetwork& network_;
  const OccupancyMap& map_;
  const StreetRouteOptions& options_;
  std::mt19937 random_;
  std::vector<int> entered_;
  std::map<std::pair<int, bool>, std::optional<TurnBack>> turns_;
};

}  // namespace

StreetRoute planStreetRoute(const StreetNetwork& network, const OccupancyMap& map,
                            const StreetRouteOptions& options) {
  return Drive(network, map, options).plan();
}

}  // namespace lineloc
