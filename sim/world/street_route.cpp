#include "sim/world/street_route.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <opencv2/imgproc.hpp>
#include <queue>
#include <random>

namespace lineloc {
namespace {

constexpr int kGoalAttempts = 200;
constexpr int kStreetAxes = 8;
constexpr int kViewRays = 31;
// The direction of travel is taken over this many cells of the path.
constexpr size_t kHeadingCells = 10;

// Where the robot drives: every cell with enough clearance, labelled by
// connected component. Goals are the cells of the largest component that lie
// on a street, between façades.
struct StreetCells {
  cv::Mat drivable;              // CV_8U 255 where the robot may drive
  std::vector<cv::Point> goals;  // street cells of the largest drivable component
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
  cv::compare(map.clearance(), options.min_clearance_m, cells.drivable, cv::CMP_GE);
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
      // Façades on both sides within the distance imply a clearance below it.
      if (largest > 0 && labels.at<int>(cell) == largest &&
          map.clearance().at<float>(cell) <= options.max_facade_distance_m &&
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
                                  double centre_weight_m) {
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
        const double clearance_m = map.clearance().at<float>(q);
        const float next =
            cost[current] + static_cast<float>(step_m * (1.0 + centre_weight_m / clearance_m));
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

// The path from the end of `path` to a random goal at least min_leg_m away,
// or empty when none is reachable. The first half of the attempts only take
// goals ahead of the direction of travel, so the robot rarely turns back.
std::vector<cv::Point> nextLeg(const OccupancyMap& map, const StreetCells& cells,
                               const std::vector<cv::Point>& path,
                               const StreetRouteOptions& options, std::mt19937& random) {
  std::uniform_int_distribution<size_t> pick(0, cells.goals.size() - 1);
  const double min_leg_cells = options.min_leg_m / map.cellSize();
  const cv::Point from = path.back();
  const cv::Point heading = from - path[path.size() - std::min(path.size(), kHeadingCells)];
  for (int attempt = 0; attempt < kGoalAttempts; ++attempt) {
    const cv::Point goal = cells.goals[pick(random)];
    const bool ahead = (goal - from).dot(heading) >= 0 || attempt >= kGoalAttempts / 2;
    if (!ahead || std::hypot(goal.x - from.x, goal.y - from.y) < min_leg_cells) {
      continue;
    }
    std::vector<cv::Point> leg =
        searchPath(map, cells.drivable, from, goal, options.centre_weight_m);
    if (!leg.empty()) {
      return leg;
    }
  }
  return {};
}

// The start and its first leg: a random goal from which the camera, looking
// along the first leg, sees façades over min_facades_in_view of its field of
// view. A start looking at open land sees nothing the model holds.
std::vector<cv::Point> firstLeg(const OccupancyMap& map, const StreetCells& cells,
                                const StreetRouteOptions& options, std::mt19937& random) {
  std::uniform_int_distribution<size_t> pick(0, cells.goals.size() - 1);
  std::vector<cv::Point> best;
  double best_share = -1.0;
  for (int attempt = 0; attempt < kGoalAttempts; ++attempt) {
    std::vector<cv::Point> leg = nextLeg(map, cells, {cells.goals[pick(random)]}, options, random);
    if (leg.empty()) {
      continue;
    }
    const cv::Point heading = leg[std::min(leg.size(), kHeadingCells) - 1] - leg.front();
    const double share = facadeShareAhead(map, leg.front(), heading, options);
    if (share >= options.min_facades_in_view) {
      return leg;
    }
    if (share > best_share) {
      best_share = share;
      best = std::move(leg);
    }
  }
  return best;
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
  std::vector<cv::Point> leg_path = firstLeg(map, cells, options, random);
  if (leg_path.empty()) {
    return route;
  }
  std::vector<cv::Point> path{leg_path.front()};
  double length_m = 0.0;
  for (int leg = 0; leg < options.max_legs && length_m < options.length_m && !leg_path.empty();
       ++leg) {
    for (size_t i = 1; i < leg_path.size() && length_m < options.length_m; ++i) {
      length_m += map.cellSize() *
                  std::hypot(leg_path[i].x - leg_path[i - 1].x, leg_path[i].y - leg_path[i - 1].y);
      path.push_back(leg_path[i]);
    }
    leg_path = nextLeg(map, cells, path, options, random);
  }
  route.waypoints = simplify(map, path, options.simplify_tolerance_m);
  route.length_m = polylineLength(route.waypoints);
  // Judged on the searched path: simplification shortens it by cutting corners.
  route.status = length_m >= options.length_m ? RouteStatus::kOk : RouteStatus::kTooShort;
  return route;
}

}  // namespace lineloc
