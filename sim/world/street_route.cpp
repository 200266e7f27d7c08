#include "sim/world/street_route.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <opencv2/imgproc.hpp>
#include <queue>
#include <random>
#include <tuple>

namespace lineloc {
namespace {

constexpr int kGoalAttempts = 200;
// Legs searched for one that keeps the façades in view, and starts tried.
constexpr int kLegSearches = 20;
constexpr int kStartAttempts = 10;
// Drives planned for one that keeps the façades in view all along.
constexpr int kRouteAttempts = 8;
constexpr int kStreetAxes = 8;
constexpr int kViewRays = 31;
// The direction of travel is taken over this many cells of the path.
constexpr size_t kHeadingCells = 10;
// Radii of the half circles the robot turns back on, widest first (m); the
// route's spline (RouteTrajectory) rounds them tighter still.
constexpr double kTurnRadii_m[] = {3.0, 2.0};

// Where the robot drives: every cell with enough clearance within reach of
// the façades, labelled by connected component. Goals are the cells of the
// largest component that lie on a street, between façades.
struct StreetCells {
  cv::Mat drivable;              // CV_8U 255 where the robot may drive
  std::vector<cv::Point> goals;  // street cells of the largest drivable component
};

// A leg of the route and the least share of the camera's view it fills with
// façades along the way.
struct Leg {
  std::vector<cv::Point> cells;
  double facades_in_view = -1.0;
  // The leg starts this many cells before the end of the drive so far, whose
  // last cells it replaces.
  size_t cut_cells = 0;
};

// True when a building cell lies within reach_cells of `cell` along `step`.
bool buildingAlong(const OccupancyMap& map, const cv::Point& cell, const Eigen::Vector2d& step,
                   int reach_cells) {
  for (int k = 1; k <= reach_cells; ++k) {
    const cv::Point at(cell.x + static_cast<int>(std::lround(k * step.x())),
                       cell.y + static_cast<int>(std::lround(k * step.y())));
    if (!map.contains(at)) {
      return false;
    }
    if (map.occupied().at<uint8_t>(at) != 0) {
      return true;
    }
  }
  return false;
}

// True when buildings stand within reach_cells of `cell` in both directions
// along one of kStreetAxes axes.
bool betweenFacades(const OccupancyMap& map, const cv::Point& cell, int reach_cells) {
  for (int axis = 0; axis < kStreetAxes; ++axis) {
    const double angle = M_PI * axis / kStreetAxes;
    const Eigen::Vector2d step(std::cos(angle), std::sin(angle));
    if (buildingAlong(map, cell, step, reach_cells) &&
        buildingAlong(map, cell, -step, reach_cells)) {
      return true;
    }
  }
  return false;
}

StreetCells findStreetCells(const OccupancyMap& map, const StreetRouteOptions& options) {
  StreetCells cells;
  cv::inRange(map.clearance(), options.min_clearance_m, options.max_facade_distance_m,
              cells.drivable);
  cv::Mat labels;
  cv::Mat stats;
  cv::Mat centroids;
  const int count =
      cv::connectedComponentsWithStats(cells.drivable, labels, stats, centroids, 8, CV_32S);
  int largest = 0;
  int largest_area = 0;
  for (int label = 1; label < count; ++label) {
    if (stats.at<int>(label, cv::CC_STAT_AREA) > largest_area) {
      largest_area = stats.at<int>(label, cv::CC_STAT_AREA);
      largest = label;
    }
  }
  const int reach_cells =
      static_cast<int>(std::ceil(options.max_facade_distance_m / map.cellSize()));
  for (int row = 0; row < map.rows(); ++row) {
    for (int col = 0; col < map.cols(); ++col) {
      const cv::Point cell(col, row);
      if (largest > 0 && labels.at<int>(cell) == largest &&
          betweenFacades(map, cell, reach_cells)) {
        cells.goals.push_back(cell);
      }
    }
  }
  return cells;
}

// A* over 8-connected drivable cells; the path from start to goal, or empty.
std::vector<cv::Point> searchPath(const OccupancyMap& map, const cv::Mat& drivable,
                                  const cv::Point& start, const cv::Point& goal,
                                  const StreetRouteOptions& options) {
  const int cols = map.cols();
  const auto index = [cols](const cv::Point& p) { return p.y * cols + p.x; };
  std::vector<float> cost(static_cast<size_t>(cols) * map.rows(),
                          std::numeric_limits<float>::infinity());
  std::vector<int> parent(cost.size(), -1);
  using Entry = std::pair<float, int>;  // (cost + heuristic, cell index)
  std::priority_queue<Entry, std::vector<Entry>, std::greater<>> open;
  const auto heuristic = [&](const cv::Point& p) {
    return static_cast<float>(map.cellSize() * std::hypot(p.x - goal.x, p.y - goal.y));
  };
  cost[index(start)] = 0.0f;
  open.push({heuristic(start), index(start)});
  while (!open.empty()) {
    const auto [priority, current] = open.top();
    open.pop();
    const cv::Point p(current % cols, current / cols);
    if (p == goal) {
      break;
    }
    if (priority > cost[current] + heuristic(p) + 1e-3f) {
      continue;  // stale entry
    }
    for (int dy = -1; dy <= 1; ++dy) {
      for (int dx = -1; dx <= 1; ++dx) {
        const cv::Point q(p.x + dx, p.y + dy);
        if ((dx == 0 && dy == 0) || !map.contains(q) || drivable.at<uint8_t>(q) == 0) {
          continue;
        }
        const double step_m = map.cellSize() * std::hypot(dx, dy);
        const double clearance_m =
            std::min<double>(map.clearance().at<float>(q), options.max_centre_clearance_m);
        const float next =
            cost[current] +
            static_cast<float>(step_m * (1.0 + options.centre_weight_m / clearance_m));
        if (next < cost[index(q)]) {
          cost[index(q)] = next;
          parent[index(q)] = current;
          open.push({next + heuristic(q), index(q)});
        }
      }
    }
  }
  std::vector<cv::Point> path;
  if (!std::isfinite(cost[index(goal)])) {
    return path;
  }
  for (int at = index(goal); at >= 0; at = parent[at]) {
    path.emplace_back(at % cols, at / cols);
  }
  std::reverse(path.begin(), path.end());
  return path;
}

// Share of the rays fanned over the camera's horizontal field of view along
// `heading` (cells) from `cell` that hit a building within the view range.
double facadeShareAhead(const OccupancyMap& map, const cv::Point& cell, const cv::Point& heading,
                        const StreetRouteOptions& options) {
  const double heading_rad = std::atan2(heading.y, heading.x);
  const double half_fov_rad = options.view_half_angle_deg * M_PI / 180.0;
  const int reach_cells = static_cast<int>(std::ceil(options.view_range_m / map.cellSize()));
  int hits = 0;
  for (int ray = 0; ray < kViewRays; ++ray) {
    const double angle = heading_rad + half_fov_rad * (2.0 * ray / (kViewRays - 1) - 1.0);
    hits +=
        buildingAlong(map, cell, Eigen::Vector2d(std::cos(angle), std::sin(angle)), reach_cells);
  }
  return static_cast<double>(hits) / kViewRays;
}

// The least share of the view filled with façades looking along `cells`, the
// camera at every kHeadingCells / 2-th cell looking kHeadingCells ahead.
double facadesInViewAlong(const OccupancyMap& map, const std::vector<cv::Point>& cells,
                          const StreetRouteOptions& options) {
  double least = 1.0;
  for (size_t i = 0; i + 1 < cells.size(); i += kHeadingCells / 2) {
    const cv::Point heading = cells[std::min(cells.size() - 1, i + kHeadingCells)] - cells[i];
    least = std::min(least, facadeShareAhead(map, cells[i], heading, options));
  }
  return least;
}

// The direction of travel at the cell `end` of `path` (zero at its first).
cv::Point headingAt(const std::vector<cv::Point>& path, size_t end) {
  return path[end] - path[end + 1 - std::min(end + 1, kHeadingCells)];
}

cv::Point headingAtEnd(const std::vector<cv::Point>& path) {
  return headingAt(path, path.size() - 1);
}

// A leg from `from` to a random goal at least min_leg_m away that keeps
// min_facades_in_view, else the one of kLegSearches with the most façades in
// view; no cells when no goal ahead is reachable. Goals and the way to them
// lie ahead of `heading`: the robot never turns back on the spot (its
// trajectory is a spline, which would cusp); turnBack turns it on an arc.
Leg nextLeg(const OccupancyMap& map, const StreetCells& cells, const cv::Point& from,
            const cv::Point& heading, const StreetRouteOptions& options, std::mt19937& random) {
  std::uniform_int_distribution<size_t> pick(0, cells.goals.size() - 1);
  const double min_leg_cells = options.min_leg_m / map.cellSize();
  Leg best;
  int searches = 0;
  for (int attempt = 0; attempt < kGoalAttempts && searches < kLegSearches; ++attempt) {
    const cv::Point goal = cells.goals[pick(random)];
    const bool ahead = (goal - from).dot(heading) >= 0;
    if (!ahead || std::hypot(goal.x - from.x, goal.y - from.y) < min_leg_cells) {
      continue;
    }
    ++searches;
    Leg leg{searchPath(map, cells.drivable, from, goal, options)};
    if (leg.cells.empty() ||
        (leg.cells[std::min(leg.cells.size() - 1, kHeadingCells)] - from).dot(heading) < 0) {
      continue;
    }
    leg.facades_in_view = facadesInViewAlong(map, leg.cells, options);
    if (leg.facades_in_view >= options.min_facades_in_view) {
      return leg;
    }
    if (leg.facades_in_view > best.facades_in_view) {
      best = std::move(leg);
    }
  }
  return best;
}

// The cells of a turn back from `from` along a non-zero `heading`: a
// diagonal to the side `side` (+1 or -1) onto a half circle of radius_m
// centred radius_m ahead of `from`, which ends radius_m to the other side of
// the way it came (the turn spans 2 radius_m across the street); empty when a
// cell of it is off the street (not between façades) or nearer than
// min_turn_clearance_m to one.
std::vector<cv::Point> turnCells(const OccupancyMap& map, const cv::Point& from,
                                 const cv::Point& heading, int side, double radius_m,
                                 const StreetRouteOptions& options) {
  const int reach_cells =
      static_cast<int>(std::ceil(options.max_facade_distance_m / map.cellSize()));
  const Eigen::Vector2d along = Eigen::Vector2d(heading.x, heading.y).normalized();
  const Eigen::Vector2d aside = side * Eigen::Vector2d(-along.y(), along.x());
  const double radius_cells = radius_m / map.cellSize();
  const Eigen::Vector2d start(from.x, from.y);
  const Eigen::Vector2d centre = start + radius_cells * along;
  // Steps of at most half a cell: the diagonal is sqrt(2) r long, the half circle pi r.
  const int diagonal_steps = static_cast<int>(std::ceil(2.0 * std::sqrt(2.0) * radius_cells));
  const int arc_steps = static_cast<int>(std::ceil(2.0 * M_PI * radius_cells));
  const auto pointAt = [&](int step) -> Eigen::Vector2d {
    if (step <= diagonal_steps) {
      return start + (radius_cells * step / diagonal_steps) * (along + aside);
    }
    const double turned = M_PI * (step - diagonal_steps) / arc_steps;
    return centre + radius_cells * (std::cos(turned) * aside + std::sin(turned) * along);
  };
  std::vector<cv::Point> turn{from};
  for (int step = 1; step <= diagonal_steps + arc_steps; ++step) {
    const Eigen::Vector2d at = pointAt(step);
    const cv::Point cell(static_cast<int>(std::lround(at.x())),
                         static_cast<int>(std::lround(at.y())));
    if (!map.contains(cell) || map.clearance().at<float>(cell) < options.min_turn_clearance_m ||
        !betweenFacades(map, cell, reach_cells)) {
      return {};
    }
    if (cell != turn.back()) {
      turn.push_back(cell);
    }
  }
  return turn;
}

// Turning back where no leg ahead keeps the façades in view (the end of a
// street that opens onto land the model does not hold): the turnCells of the
// widest of kTurnRadii_m that stay on the street, to either side, from the
// end of `path` or, where the street ends too soon for that, from the
// turn's width before it; then a leg ahead in the opposite direction. The
// leg with the most façades in view; no cells when no turn fits.
Leg turnBack(const OccupancyMap& map, const StreetCells& cells, const std::vector<cv::Point>& path,
             const StreetRouteOptions& options, std::mt19937& random) {
  Leg best;
  for (const double radius_m : kTurnRadii_m) {
    const size_t turn_width_cells = static_cast<size_t>(std::ceil(2.0 * radius_m / map.cellSize()));
    for (const size_t cut : {size_t{0}, turn_width_cells}) {
      if (cut + 1 >= path.size()) {
        continue;
      }
      const size_t end = path.size() - 1 - cut;
      const cv::Point heading = headingAt(path, end);
      if (heading == cv::Point(0, 0)) {
        continue;
      }
      for (const int side : {1, -1}) {
        std::vector<cv::Point> turn = turnCells(map, path[end], heading, side, radius_m, options);
        if (turn.empty()) {
          continue;
        }
        const Leg onwards = nextLeg(map, cells, turn.back(), -heading, options, random);
        if (onwards.cells.empty()) {
          continue;
        }
        turn.insert(turn.end(), onwards.cells.begin() + 1, onwards.cells.end());
        Leg leg{std::move(turn), 0.0, cut};
        leg.facades_in_view = facadesInViewAlong(map, leg.cells, options);
        if (leg.facades_in_view > best.facades_in_view) {
          best = std::move(leg);
        }
      }
      if (!best.cells.empty()) {
        return best;
      }
    }
  }
  return best;
}

// The next leg from the end of `path`: onwards, or back where onwards keeps
// fewer façades in view than min_facades_in_view and turning back more.
Leg legAfter(const OccupancyMap& map, const StreetCells& cells, const std::vector<cv::Point>& path,
             const StreetRouteOptions& options, std::mt19937& random) {
  Leg onwards = nextLeg(map, cells, path.back(), headingAtEnd(path), options, random);
  if (onwards.facades_in_view >= options.min_facades_in_view) {
    return onwards;
  }
  Leg back = turnBack(map, cells, path, options, random);
  return back.facades_in_view > onwards.facades_in_view ? std::move(back) : std::move(onwards);
}

// The start and its first leg: the first leg from a random goal that keeps
// min_facades_in_view, else the best found from kStartAttempts goals.
Leg firstLeg(const OccupancyMap& map, const StreetCells& cells, const StreetRouteOptions& options,
             std::mt19937& random) {
  std::uniform_int_distribution<size_t> pick(0, cells.goals.size() - 1);
  Leg best;
  for (int attempt = 0; attempt < kStartAttempts; ++attempt) {
    Leg leg = nextLeg(map, cells, cells.goals[pick(random)], cv::Point(0, 0), options, random);
    if (leg.facades_in_view >= options.min_facades_in_view) {
      return leg;
    }
    if (leg.facades_in_view > best.facades_in_view) {
      best = std::move(leg);
    }
  }
  return best;
}

// A drive of whole legs from a random start until length_m, and the least
// share of the view filled with façades along its legs.
struct CellRoute {
  std::vector<cv::Point> cells;
  double length_m = 0.0;
  double facades_in_view = 1.0;
};

double stepLength_m(const OccupancyMap& map, const cv::Point& from, const cv::Point& to) {
  return map.cellSize() * std::hypot(to.x - from.x, to.y - from.y);
}

CellRoute driveLegs(const OccupancyMap& map, const StreetCells& cells,
                    const StreetRouteOptions& options, std::mt19937& random) {
  CellRoute drive;
  Leg leg = firstLeg(map, cells, options, random);
  if (leg.cells.empty()) {
    return drive;
  }
  drive.cells.push_back(leg.cells.front());
  for (int count = 0;
       count < options.max_legs && drive.length_m < options.length_m && !leg.cells.empty();
       ++count) {
    drive.facades_in_view = std::min(drive.facades_in_view, leg.facades_in_view);
    for (size_t cut = 0; cut < leg.cut_cells; ++cut) {
      drive.length_m -= stepLength_m(map, drive.cells[drive.cells.size() - 2], drive.cells.back());
      drive.cells.pop_back();
    }
    for (size_t i = 1; i < leg.cells.size() && drive.length_m < options.length_m; ++i) {
      drive.length_m += stepLength_m(map, leg.cells[i - 1], leg.cells[i]);
      drive.cells.push_back(leg.cells[i]);
    }
    leg = legAfter(map, cells, drive.cells, options, random);
  }
  return drive;
}

std::vector<Eigen::Vector2d> simplify(const OccupancyMap& map, const std::vector<cv::Point>& cells,
                                      double tolerance_m) {
  std::vector<cv::Point2f> points;
  for (const cv::Point& cell : cells) {
    const Eigen::Vector2d xy = map.centreOf(cell);
    points.emplace_back(static_cast<float>(xy.x()), static_cast<float>(xy.y()));
  }
  std::vector<cv::Point2f> simplified;
  cv::approxPolyDP(points, simplified, tolerance_m, false);
  std::vector<Eigen::Vector2d> waypoints;
  for (const cv::Point2f& point : simplified) {
    waypoints.emplace_back(point.x, point.y);
  }
  return waypoints;
}

}  // namespace

double polylineLength(const std::vector<Eigen::Vector2d>& points) {
  double length = 0.0;
  for (size_t i = 1; i < points.size(); ++i) {
    length += (points[i] - points[i - 1]).norm();
  }
  return length;
}

StreetRoute planStreetRoute(const OccupancyMap& map, const StreetRouteOptions& options) {
  StreetRoute route;
  const StreetCells cells = findStreetCells(map, options);
  if (cells.goals.empty()) {
    return route;
  }
  std::mt19937 random(options.seed);
  const auto rank = [&](const CellRoute& drive) {
    return std::make_tuple(drive.length_m >= options.length_m, drive.facades_in_view,
                           drive.length_m);
  };
  CellRoute best;
  for (int attempt = 0; attempt < kRouteAttempts; ++attempt) {
    CellRoute drive = driveLegs(map, cells, options, random);
    if (attempt == 0 || rank(drive) > rank(best)) {
      best = std::move(drive);
    }
    if (std::get<0>(rank(best)) && best.facades_in_view >= options.min_facades_in_view) {
      break;
    }
  }
  if (best.cells.empty()) {
    return route;
  }
  route.waypoints = simplify(map, best.cells, options.simplify_tolerance_m);
  route.length_m = polylineLength(route.waypoints);
  // Judged on the searched path: simplification shortens it by cutting corners.
  route.status = best.length_m >= options.length_m ? RouteStatus::kOk : RouteStatus::kTooShort;
  return route;
}

}  // namespace lineloc
