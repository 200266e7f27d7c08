#include "sim/world/street_network.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <opencv2/imgproc.hpp>
#include <opencv2/ximgproc.hpp>

namespace lineloc {
namespace {

constexpr int kStreetAxes = 8;
constexpr int kNoNode = -1;

// A node or edge of the graph while it is cleaned: removed edges stay in
// place (alive = false) so that indices hold, and a node without alive edges
// is left out of the network.
struct WorkNode {
  Eigen::Vector2d xy_sum = Eigen::Vector2d::Zero();
  int cell_count = 0;
  double clearance_m = 0.0;
  Eigen::Vector2d xy() const { return xy_sum / cell_count; }
};

struct WorkEdge {
  int from = kNoNode;
  int to = kNoNode;
  std::vector<Eigen::Vector2d> polyline;
  double length_m = 0.0;
  bool alive = true;
  bool isLoop() const { return from == to; }
};

struct WorkGraph {
  std::vector<WorkNode> nodes;
  std::vector<WorkEdge> edges;

  std::vector<int> degrees() const {
    std::vector<int> degree(nodes.size(), 0);
    for (const WorkEdge& edge : edges) {
      if (edge.alive) {
        ++degree[edge.from];
        ++degree[edge.to];
      }
    }
    return degree;
  }
  // The alive edges at every node (a loop twice).
  std::vector<std::vector<int>> incidence() const {
    std::vector<std::vector<int>> at(nodes.size());
    for (size_t e = 0; e < edges.size(); ++e) {
      if (edges[e].alive) {
        at[edges[e].from].push_back(static_cast<int>(e));
        at[edges[e].to].push_back(static_cast<int>(e));
      }
    }
    return at;
  }
};

// True when buildings stand within reach_m of `cell` in both directions along
// one of kStreetAxes axes.
bool betweenFacades(const OccupancyMap& map, const cv::Point& cell, double reach_m) {
  for (int axis = 0; axis < kStreetAxes; ++axis) {
    const double angle = M_PI * axis / kStreetAxes;
    const Eigen::Vector2d step(std::cos(angle), std::sin(angle));
    if (map.buildingAlong(cell, step, reach_m) && map.buildingAlong(cell, -step, reach_m)) {
      return true;
    }
  }
  return false;
}

// CV_8U, 255 on the street cells.
cv::Mat streetCells(const OccupancyMap& map, const StreetNetworkOptions& options) {
  cv::Mat cells;
  cv::inRange(map.clearance(), options.min_clearance_m, options.max_facade_distance_m, cells);
  for (int row = 0; row < map.rows(); ++row) {
    for (int col = 0; col < map.cols(); ++col) {
      uint8_t& cell = cells.at<uint8_t>(row, col);
      if (cell != 0 && !betweenFacades(map, cv::Point(col, row), options.max_facade_distance_m)) {
        cell = 0;
      }
    }
  }
  return cells;
}

// The skeleton pixels that are 8-neighbours of `pixel`.
std::vector<cv::Point> skeletonNeighbours(const cv::Mat& skeleton, const cv::Point& pixel) {
  std::vector<cv::Point> neighbours;
  for (int dy = -1; dy <= 1; ++dy) {
    for (int dx = -1; dx <= 1; ++dx) {
      const cv::Point q(pixel.x + dx, pixel.y + dy);
      if ((dx != 0 || dy != 0) && q.x >= 0 && q.y >= 0 && q.x < skeleton.cols &&
          q.y < skeleton.rows && skeleton.at<uint8_t>(q) != 0) {
        neighbours.push_back(q);
      }
    }
  }
  return neighbours;
}

// Nodes of the skeleton: every 8-connected cluster of junction pixels (three
// or more neighbours) and every dead-end pixel (one neighbour); the node of
// every pixel in `node_of` (CV_32S, kNoNode elsewhere).
WorkGraph skeletonNodes(const OccupancyMap& map, const cv::Mat& skeleton, cv::Mat& node_of) {
  cv::Mat junctions = cv::Mat::zeros(skeleton.size(), CV_8U);
  cv::Mat dead_ends = cv::Mat::zeros(skeleton.size(), CV_8U);
  for (int row = 0; row < skeleton.rows; ++row) {
    for (int col = 0; col < skeleton.cols; ++col) {
      if (skeleton.at<uint8_t>(row, col) == 0) {
        continue;
      }
      const size_t degree = skeletonNeighbours(skeleton, cv::Point(col, row)).size();
      junctions.at<uint8_t>(row, col) = degree >= 3 ? 255 : 0;
      dead_ends.at<uint8_t>(row, col) = degree == 1 ? 255 : 0;
    }
  }
  cv::Mat junction_labels;
  const int junction_count = cv::connectedComponents(junctions, junction_labels, 8, CV_32S) - 1;
  WorkGraph graph;
  graph.nodes.resize(junction_count);
  node_of = cv::Mat(skeleton.size(), CV_32S, cv::Scalar(kNoNode));
  for (int row = 0; row < skeleton.rows; ++row) {
    for (int col = 0; col < skeleton.cols; ++col) {
      int node = kNoNode;
      if (junction_labels.at<int>(row, col) > 0) {
        node = junction_labels.at<int>(row, col) - 1;
      } else if (dead_ends.at<uint8_t>(row, col) != 0) {
        node = static_cast<int>(graph.nodes.size());
        graph.nodes.emplace_back();
      } else {
        continue;
      }
      const cv::Point cell(col, row);
      node_of.at<int>(cell) = node;
      WorkNode& work = graph.nodes[node];
      work.xy_sum += map.centreOf(cell);
      ++work.cell_count;
      work.clearance_m = std::max<double>(work.clearance_m, map.clearance().at<float>(cell));
    }
  }
  return graph;
}

// The edges of the skeleton: chains of two-neighbour pixels from a node to a
// node (or one node pixel next to another node's).
void traceEdges(const OccupancyMap& map, const cv::Mat& skeleton, const cv::Mat& node_of,
                WorkGraph& graph) {
  cv::Mat traced = cv::Mat::zeros(skeleton.size(), CV_8U);
  const auto addEdge = [&](const std::vector<cv::Point>& pixels) {
    WorkEdge edge;
    edge.from = node_of.at<int>(pixels.front());
    edge.to = node_of.at<int>(pixels.back());
    for (const cv::Point& pixel : pixels) {
      edge.polyline.push_back(map.centreOf(pixel));
    }
    edge.length_m = polylineLength(edge.polyline);
    graph.edges.push_back(std::move(edge));
  };
  for (int row = 0; row < skeleton.rows; ++row) {
    for (int col = 0; col < skeleton.cols; ++col) {
      const cv::Point start(col, row);
      const int node = node_of.at<int>(start);
      if (node == kNoNode) {
        continue;
      }
      for (const cv::Point& first : skeletonNeighbours(skeleton, start)) {
        const int first_node = node_of.at<int>(first);
        if (first_node != kNoNode) {
          if (node < first_node) {
            addEdge({start, first});
          }
          continue;
        }
        if (traced.at<uint8_t>(first) != 0) {
          continue;
        }
        std::vector<cv::Point> pixels{start, first};
        traced.at<uint8_t>(first) = 255;
        while (node_of.at<int>(pixels.back()) == kNoNode) {
          const cv::Point previous = pixels[pixels.size() - 2];
          const std::vector<cv::Point> next = skeletonNeighbours(skeleton, pixels.back());
          const auto onwards = std::find_if(next.begin(), next.end(), [&](const cv::Point& q) {
            return q != previous && (node_of.at<int>(q) != kNoNode || traced.at<uint8_t>(q) == 0);
          });
          if (onwards == next.end()) {
            break;
          }
          traced.at<uint8_t>(*onwards) = 255;
          pixels.push_back(*onwards);
        }
        if (node_of.at<int>(pixels.back()) != kNoNode) {
          addEdge(pixels);
        }
      }
    }
  }
}

// Removes the spurs shorter than the street width at their junction and the
// loops that lie within their node's largest empty disc (shorter than 2 pi c).
bool removeNoise(WorkGraph& graph) {
  const std::vector<int> degree = graph.degrees();
  bool changed = false;
  for (WorkEdge& edge : graph.edges) {
    if (!edge.alive) {
      continue;
    }
    if (edge.isLoop()) {
      if (edge.length_m < 2.0 * M_PI * graph.nodes[edge.from].clearance_m) {
        edge.alive = false;
        changed = true;
      }
      continue;
    }
    if ((degree[edge.from] == 1) == (degree[edge.to] == 1)) {
      continue;
    }
    const int junction = degree[edge.from] == 1 ? edge.to : edge.from;
    if (degree[junction] >= 3 && edge.length_m < 2.0 * graph.nodes[junction].clearance_m) {
      edge.alive = false;
      changed = true;
    }
  }
  return changed;
}

// Merges the junctions joined by an edge shorter than the larger of their
// clearances.
bool mergeCrossings(WorkGraph& graph) {
  const std::vector<int> degree = graph.degrees();
  bool changed = false;
  for (size_t e = 0; e < graph.edges.size(); ++e) {
    WorkEdge& edge = graph.edges[e];
    if (!edge.alive || edge.isLoop() || degree[edge.from] < 3 || degree[edge.to] < 3) {
      continue;
    }
    WorkNode& kept = graph.nodes[edge.from];
    WorkNode& merged = graph.nodes[edge.to];
    if (edge.length_m >= std::max(kept.clearance_m, merged.clearance_m)) {
      continue;
    }
    kept.xy_sum += merged.xy_sum;
    kept.cell_count += merged.cell_count;
    kept.clearance_m = std::max(kept.clearance_m, merged.clearance_m);
    edge.alive = false;
    const int kept_index = edge.from;
    const int merged_index = edge.to;
    for (WorkEdge& other : graph.edges) {
      other.from = other.from == merged_index ? kept_index : other.from;
      other.to = other.to == merged_index ? kept_index : other.to;
    }
    changed = true;
  }
  return changed;
}

// Joins the two edges of every node that has two.
bool joinChains(WorkGraph& graph) {
  std::vector<std::vector<int>> incidence = graph.incidence();
  bool changed = false;
  for (size_t n = 0; n < graph.nodes.size(); ++n) {
    const int node = static_cast<int>(n);
    if (incidence[n].size() != 2 || incidence[n][0] == incidence[n][1]) {
      continue;
    }
    WorkEdge& first = graph.edges[incidence[n][0]];
    WorkEdge& second = graph.edges[incidence[n][1]];
    if (first.to != node) {
      std::swap(first.from, first.to);
      std::reverse(first.polyline.begin(), first.polyline.end());
    }
    if (second.from != node) {
      std::swap(second.from, second.to);
      std::reverse(second.polyline.begin(), second.polyline.end());
    }
    first.polyline.insert(first.polyline.end(), second.polyline.begin() + 1, second.polyline.end());
    first.length_m += second.length_m;
    first.to = second.to;
    second.alive = false;
    std::replace(incidence[second.to].begin(), incidence[second.to].end(), incidence[n][1],
                 incidence[n][0]);
    incidence[n].clear();
    changed = true;
  }
  return changed;
}

std::vector<Eigen::Vector2d> simplify(const std::vector<Eigen::Vector2d>& polyline,
                                      double tolerance_m) {
  // Site-frame coordinates: float keeps millimetres within 10 km.
  std::vector<cv::Point2f> points;
  for (const Eigen::Vector2d& xy : polyline) {
    points.emplace_back(static_cast<float>(xy.x()), static_cast<float>(xy.y()));
  }
  std::vector<cv::Point2f> simplified;
  cv::approxPolyDP(points, simplified, tolerance_m, false);
  std::vector<Eigen::Vector2d> result;
  for (const cv::Point2f& point : simplified) {
    result.emplace_back(point.x, point.y);
  }
  return result;
}

// The alive part of `graph`, its edges snapped to their nodes and simplified.
StreetNetwork compact(const WorkGraph& graph, double simplify_tolerance_m) {
  StreetNetwork network;
  std::vector<int> index(graph.nodes.size(), kNoNode);
  const auto nodeIndex = [&](int work_node) {
    if (index[work_node] == kNoNode) {
      index[work_node] = static_cast<int>(network.nodes.size());
      network.nodes.push_back(
          {graph.nodes[work_node].xy(), graph.nodes[work_node].clearance_m, {}});
    }
    return index[work_node];
  };
  for (const WorkEdge& work : graph.edges) {
    if (!work.alive) {
      continue;
    }
    StreetNetwork::Edge edge;
    edge.from = nodeIndex(work.from);
    edge.to = nodeIndex(work.to);
    edge.polyline = work.polyline;
    edge.polyline.front() = network.nodes[edge.from].xy;
    edge.polyline.back() = network.nodes[edge.to].xy;
    edge.polyline = simplify(edge.polyline, simplify_tolerance_m);
    edge.length_m = polylineLength(edge.polyline);
    const int e = static_cast<int>(network.edges.size());
    network.nodes[edge.from].edges.push_back(e);
    network.nodes[edge.to].edges.push_back(e);
    network.edges.push_back(std::move(edge));
  }
  return network;
}

}  // namespace

double polylineLength(const std::vector<Eigen::Vector2d>& points) {
  double length = 0.0;
  for (size_t i = 1; i < points.size(); ++i) {
    length += (points[i] - points[i - 1]).norm();
  }
  return length;
}

std::vector<int> StreetNetwork::components() const {
  // Union-find over the edges.
  std::vector<int> parent(nodes.size());
  std::iota(parent.begin(), parent.end(), 0);
  const auto root = [&](int node) {
    while (parent[node] != node) {
      node = parent[node] = parent[parent[node]];
    }
    return node;
  };
  for (const Edge& edge : edges) {
    parent[root(edge.from)] = root(edge.to);
  }
  std::vector<double> length_m(nodes.size(), 0.0);
  for (const Edge& edge : edges) {
    length_m[root(edge.from)] += edge.length_m;
  }
  std::vector<int> roots;
  for (size_t n = 0; n < nodes.size(); ++n) {
    if (root(static_cast<int>(n)) == static_cast<int>(n)) {
      roots.push_back(static_cast<int>(n));
    }
  }
  std::stable_sort(roots.begin(), roots.end(),
                   [&](int a, int b) { return length_m[a] > length_m[b]; });
  std::vector<int> component_of_root(nodes.size(), 0);
  for (size_t k = 0; k < roots.size(); ++k) {
    component_of_root[roots[k]] = static_cast<int>(k);
  }
  std::vector<int> component(nodes.size());
  for (size_t n = 0; n < nodes.size(); ++n) {
    component[n] = component_of_root[root(static_cast<int>(n))];
  }
  return component;
}

StreetNetwork buildStreetNetwork(const OccupancyMap& map, const StreetNetworkOptions& options) {
  cv::Mat skeleton;
  cv::ximgproc::thinning(streetCells(map, options), skeleton, cv::ximgproc::THINNING_ZHANGSUEN);
  cv::Mat node_of;
  WorkGraph graph = skeletonNodes(map, skeleton, node_of);
  traceEdges(map, skeleton, node_of, graph);
  for (bool changed = true; changed;) {
    changed = removeNoise(graph);
    changed = mergeCrossings(graph) || changed;
    changed = joinChains(graph) || changed;
  }
  return compact(graph, options.simplify_tolerance_m);
}

}  // namespace lineloc
