#include "sim/world/occupancy_map.h"

#include <fmt/format.h>

#include <cmath>
#include <opencv2/imgproc.hpp>
#include <stdexcept>

namespace lineloc {
namespace {

bool isBuilding(SurfaceKind kind) {
  return kind == SurfaceKind::kWall || kind == SurfaceKind::kRoof;
}

}  // namespace

OccupancyMap::OccupancyMap(const SceneMesh& mesh, double cell_size_m, double margin_m)
    : cell_size_m_(cell_size_m) {
  if (!(cell_size_m > 0.0) || !(margin_m >= 0.0)) {
    throw std::invalid_argument(fmt::format(
        "OccupancyMap: cell size {} m must be > 0 and margin {} m >= 0", cell_size_m, margin_m));
  }
  for (size_t i = 0; i < mesh.triangleCount(); ++i) {
    if (isBuilding(mesh.tag(i).kind)) {
      for (int k = 0; k < 3; ++k) {
        building_bounds_.extend(mesh.vertices()[3 * i + k].head<2>().cast<double>());
      }
    }
  }
  if (building_bounds_.isEmpty()) {
    throw std::invalid_argument("OccupancyMap: the mesh has no wall or roof triangles");
  }
  origin_ = building_bounds_.min() - Eigen::Vector2d::Constant(margin_m);
  const Eigen::Vector2d extent = building_bounds_.sizes() + Eigen::Vector2d::Constant(2 * margin_m);
  occupied_ = cv::Mat::zeros(static_cast<int>(std::ceil(extent.y() / cell_size_m)) + 1,
                             static_cast<int>(std::ceil(extent.x() / cell_size_m)) + 1, CV_8UC1);
  for (size_t i = 0; i < mesh.triangleCount(); ++i) {
    if (!isBuilding(mesh.tag(i).kind)) {
      continue;
    }
    cv::Point corners[3];
    for (int k = 0; k < 3; ++k) {
      corners[k] = cellOf(mesh.vertices()[3 * i + k].head<2>().cast<double>());
    }
    // Walls project to segments, roofs to areas; both block the street.
    cv::fillConvexPoly(occupied_, corners, 3, cv::Scalar(255));
    cv::polylines(occupied_, std::vector<cv::Point>(corners, corners + 3), true, cv::Scalar(255));
  }
  cv::Mat free_cells = 255 - occupied_;
  cv::distanceTransform(free_cells, clearance_m_, cv::DIST_L2, cv::DIST_MASK_PRECISE);
  clearance_m_ *= cell_size_m_;
}

cv::Point OccupancyMap::cellOf(const Eigen::Vector2d& xy) const {
  const Eigen::Vector2d cell = (xy - origin_) / cell_size_m_;
  return {static_cast<int>(std::floor(cell.x())), static_cast<int>(std::floor(cell.y()))};
}

Eigen::Vector2d OccupancyMap::centreOf(const cv::Point& cell) const {
  return origin_ + cell_size_m_ * Eigen::Vector2d(cell.x + 0.5, cell.y + 0.5);
}

bool OccupancyMap::contains(const cv::Point& cell) const {
  return cell.x >= 0 && cell.y >= 0 && cell.x < cols() && cell.y < rows();
}

double OccupancyMap::clearanceAt(const Eigen::Vector2d& xy) const {
  const cv::Point cell = cellOf(xy);
  return contains(cell) ? clearance_m_.at<float>(cell) : 0.0;
}

bool OccupancyMap::buildingAlong(const cv::Point& cell, const Eigen::Vector2d& direction,
                                 double range_m) const {
  const int reach_cells = static_cast<int>(std::ceil(range_m / cell_size_m_));
  for (int k = 1; k <= reach_cells; ++k) {
    const cv::Point at(cell.x + static_cast<int>(std::lround(k * direction.x())),
                       cell.y + static_cast<int>(std::lround(k * direction.y())));
    if (!contains(at)) {
      return false;
    }
    if (occupied_.at<uint8_t>(at) != 0) {
      return true;
    }
  }
  return false;
}

Eigen::Vector2d OccupancyMap::awayFromBuildings(const Eigen::Vector2d& xy) const {
  const cv::Point cell = cellOf(xy);
  if (cell.x < 1 || cell.y < 1 || cell.x >= cols() - 1 || cell.y >= rows() - 1) {
    return Eigen::Vector2d::Zero();
  }
  // Central differences of the clearance.
  const Eigen::Vector2d gradient(
      clearance_m_.at<float>(cell.y, cell.x + 1) - clearance_m_.at<float>(cell.y, cell.x - 1),
      clearance_m_.at<float>(cell.y + 1, cell.x) - clearance_m_.at<float>(cell.y - 1, cell.x));
  const double norm = gradient.norm();
  return norm > 1e-6 ? Eigen::Vector2d(gradient / norm) : Eigen::Vector2d::Zero();
}

}  // namespace lineloc
