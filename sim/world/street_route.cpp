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

// Street cells: enough clearance; labelled by connected component.
struct StreetCells {
  cv::Mat drivable;              // CV_8U 255 where the robot may drive
  cv::Mat labels;                // CV_32S component of every drivable cell
  int largest = 0;               // label of the largest component
  std::vector<cv::Point> goals;  // drivable cells of the largest component near buildings
};

StreetCells findStreetCells(const OccupancyMap& map, const StreetRouteOptions& options) {
  StreetCells cells;
  cv::compare(map.clearance(), options.min_clearance_m, cells.drivable, cv::CMP_GE);
  cv::Mat stats;
  cv::Mat centroids;
  const int count =
      cv::connectedComponentsWithStats(cells.drivable, cells.labels, stats, centroids, 8, CV_32S);
  int largest_area = 0;
  for (int label = 1; label < count; ++label) {
    if (stats.at<int>(label, cv::CC_STAT_AREA) > largest_area) {
      largest_area = stats.at<int>(label, cv::CC_STAT_AREA);
      cells.largest = label;
    }
  }
  // Goals lie inside the convex hull of the footprints: among the buildings,
  // not along the outside of the modelled area.
  std::vector<cv::Point> building_cells;
  cv::findNonZero(map.occupied(), building_cells);
  std::vector<cv::Point> hull;
  cv::convexHull(building_cells, hull);
  cv::Mat among_buildings = cv::Mat::zeros(map.rows(), map.cols(), CV_8UC1);
  cv::fillConvexPoly(among_buildings, hull, cv::Scalar(255));
  for (int row = 0; row < map.rows(); ++row) {
    for (int col = 0; col < map.cols(); ++col) {
      const cv::Point cell(col, row);
      if (cells.largest > 0 && cells.labels.at<int>(cell) == cells.largest &&
          map.clearance().at<float>(cell) <= options.max_clearance_m &&
          among_buildings.at<uint8_t>(cell) != 0) {
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
  std::uniform_int_distribution<size_t> pick(0, cells.goals.size() - 1);
  std::vector<cv::Point> path{cells.goals[pick(random)]};
  double length_m = 0.0;
  const double min_leg_cells = options.min_leg_m / map.cellSize();
  for (int leg = 0; leg < options.max_legs && length_m < options.length_m; ++leg) {
    const cv::Point from = path.back();
    // Direction of travel over the last few metres; the first half of the
    // attempts only take goals ahead of it, so the robot rarely turns back.
    const cv::Point heading = from - path[path.size() - std::min<size_t>(path.size(), 10)];
    std::vector<cv::Point> leg_path;
    for (int attempt = 0; attempt < kGoalAttempts && leg_path.empty(); ++attempt) {
      const cv::Point goal = cells.goals[pick(random)];
      const bool ahead = (goal - from).dot(heading) >= 0 || attempt >= kGoalAttempts / 2;
      if (ahead && std::hypot(goal.x - from.x, goal.y - from.y) >= min_leg_cells) {
        leg_path = searchPath(map, cells.drivable, from, goal, options.centre_weight_m);
      }
    }
    if (leg_path.empty()) {
      break;
    }
    for (size_t i = 1; i < leg_path.size() && length_m < options.length_m; ++i) {
      length_m += map.cellSize() *
                  std::hypot(leg_path[i].x - leg_path[i - 1].x, leg_path[i].y - leg_path[i - 1].y);
      path.push_back(leg_path[i]);
    }
  }
  route.waypoints = simplify(map, path, options.simplify_tolerance_m);
  route.length_m = polylineLength(route.waypoints);
  // Judged on the searched path: simplification shortens it by cutting corners.
  route.status = length_m >= options.length_m ? RouteStatus::kOk : RouteStatus::kTooShort;
  return route;
}

}  // namespace lineloc
