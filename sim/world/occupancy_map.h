// Where the buildings stand, seen from above: the building triangles of a
// SceneMesh rasterised into a grid over their bounding box, with every cell's
// clearance (distance to the nearest building, from OpenCV's exact Euclidean
// distance transform). Street routes and street furniture are placed in it.
#pragma once

#include <Eigen/Core>
#include <opencv2/core.hpp>

#include "sim/render/scene_mesh.h"

namespace lineloc {

class OccupancyMap {
 public:
  // Rasterises the kWall and kRoof triangles of `mesh` into cells of `cell_size_m`
  // over their xy bounding box grown by `margin_m`. Throws std::invalid_argument
  // when the mesh has no building triangles or the cell size is not positive.
  OccupancyMap(const SceneMesh& mesh, double cell_size_m = 0.5, double margin_m = 10.0);

  double cellSize() const { return cell_size_m_; }
  int cols() const { return occupied_.cols; }
  int rows() const { return occupied_.rows; }
  // Cell (col, row) of a world point and the world centre of a cell.
  cv::Point cellOf(const Eigen::Vector2d& xy) const;
  Eigen::Vector2d centreOf(const cv::Point& cell) const;
  bool contains(const cv::Point& cell) const;

  // CV_8U, 255 where a building stands.
  const cv::Mat& occupied() const { return occupied_; }
  // CV_32F, metres from each cell to the nearest building cell.
  const cv::Mat& clearance() const { return clearance_m_; }
  double clearanceAt(const Eigen::Vector2d& xy) const;
  // True when a building cell lies within range_m of `cell` along the unit
  // `direction` (cells stepped one cell length apart; the grid's edge ends the
  // search).
  bool buildingAlong(const cv::Point& cell, const Eigen::Vector2d& direction, double range_m) const;
  // Unit vector pointing away from the nearest building (the clearance
  // gradient); zero where the clearance is flat.
  Eigen::Vector2d awayFromBuildings(const Eigen::Vector2d& xy) const;
  // xy bounding box of the building triangles (without the margin).
  const Eigen::AlignedBox2d& buildingBounds() const { return building_bounds_; }

 private:
  double cell_size_m_;
  Eigen::Vector2d origin_;  // world xy of cell (0, 0)'s corner
  Eigen::AlignedBox2d building_bounds_;
  cv::Mat occupied_;
  cv::Mat clearance_m_;
};

}  // namespace lineloc
