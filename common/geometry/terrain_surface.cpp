#include "common/geometry/terrain_surface.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace lineloc {
namespace {

// Twice the signed area of the triangle a, b, c.
double doubleArea(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c) {
  return (b.x() - a.x()) * (c.y() - a.y()) - (b.y() - a.y()) * (c.x() - a.x());
}

// The triangle's height at `xy` when its ground projection holds it.
std::optional<double> heightWithin(const TerrainSurface::Triangle& triangle,
                                   const Eigen::Vector2d& xy) {
  const Eigen::Vector2d a = triangle[0].head<2>();
  const Eigen::Vector2d b = triangle[1].head<2>();
  const Eigen::Vector2d c = triangle[2].head<2>();
  const double area = doubleArea(a, b, c);
  if (!(std::abs(area) > 0.0)) {
    return std::nullopt;
  }
  const double b0 = doubleArea(xy, b, c) / area;
  const double b1 = doubleArea(a, xy, c) / area;
  const double b2 = 1.0 - b0 - b1;
  // A point on an edge shared by two triangles belongs to both, despite rounding.
  constexpr double kOnEdge = -1e-12;
  if (b0 < kOnEdge || b1 < kOnEdge || b2 < kOnEdge) {
    return std::nullopt;
  }
  return b0 * triangle[0].z() + b1 * triangle[1].z() + b2 * triangle[2].z();
}

}  // namespace

TerrainSurface::TerrainSurface(std::vector<Triangle> triangles, double cell_size_m)
    : triangles_(std::move(triangles)), cell_size_m_(cell_size_m) {
  if (!(cell_size_m_ > 0.0)) {
    throw std::invalid_argument("TerrainSurface: cell_size_m must be positive");
  }
  Eigen::AlignedBox2d bounds;
  for (const Triangle& triangle : triangles_) {
    for (const Eigen::Vector3d& corner : triangle) {
      if (!corner.allFinite()) {
        throw std::invalid_argument("TerrainSurface: a triangle has a non-finite corner");
      }
      bounds.extend(corner.head<2>());
    }
  }
  if (triangles_.empty()) {
    return;
  }
  if (!bounds.sizes().allFinite()) {
    throw std::invalid_argument("TerrainSurface: the terrain's extent overflows");
  }
  grid_origin_ = bounds.min();
  // Cells no smaller than needed to keep their count within kCellsPerTriangle
  // per triangle, however large the terrain's extent.
  constexpr double kCellsPerTriangle = 4.0;
  const double max_cells = kCellsPerTriangle * static_cast<double>(triangles_.size()) + 16.0;
  cell_size_m_ =
      std::max(cell_size_m_, std::sqrt(bounds.sizes().x() * bounds.sizes().y() / max_cells));
  cell_size_m_ = std::max(cell_size_m_, bounds.sizes().maxCoeff() / max_cells);
  columns_ = static_cast<int>(std::floor(bounds.sizes().x() / cell_size_m_)) + 1;
  rows_ = static_cast<int>(std::floor(bounds.sizes().y() / cell_size_m_)) + 1;
  // Counting sort of (cell, triangle) pairs by cell.
  const auto cellRange = [&](const Triangle& triangle) {
    Eigen::AlignedBox2d box;
    for (const Eigen::Vector3d& corner : triangle) {
      box.extend(corner.head<2>());
    }
    const Eigen::Vector2d low = (box.min() - grid_origin_) / cell_size_m_;
    const Eigen::Vector2d high = (box.max() - grid_origin_) / cell_size_m_;
    return std::array<int, 4>{static_cast<int>(low.x()), static_cast<int>(low.y()),
                              std::min(static_cast<int>(high.x()), columns_ - 1),
                              std::min(static_cast<int>(high.y()), rows_ - 1)};
  };
  cell_start_.assign(static_cast<size_t>(columns_) * rows_ + 1, 0);
  for (const Triangle& triangle : triangles_) {
    const auto [x0, y0, x1, y1] = cellRange(triangle);
    for (int row = y0; row <= y1; ++row) {
      for (int column = x0; column <= x1; ++column) {
        ++cell_start_[static_cast<size_t>(row) * columns_ + column + 1];
      }
    }
  }
  for (size_t cell = 1; cell < cell_start_.size(); ++cell) {
    cell_start_[cell] += cell_start_[cell - 1];
  }
  cell_triangles_.resize(static_cast<size_t>(cell_start_.back()));
  std::vector<int> next(cell_start_.begin(), cell_start_.end() - 1);
  for (size_t index = 0; index < triangles_.size(); ++index) {
    const auto [x0, y0, x1, y1] = cellRange(triangles_[index]);
    for (int row = y0; row <= y1; ++row) {
      for (int column = x0; column <= x1; ++column) {
        cell_triangles_[static_cast<size_t>(next[static_cast<size_t>(row) * columns_ + column]++)] =
            static_cast<int>(index);
      }
    }
  }
}

std::optional<double> TerrainSurface::heightAt(const Eigen::Vector2d& xy) const {
  if (triangles_.empty() || !xy.allFinite()) {
    return std::nullopt;
  }
  const Eigen::Vector2d cell = ((xy - grid_origin_) / cell_size_m_).array().floor();
  if (cell.x() < 0.0 || cell.y() < 0.0 || cell.x() >= columns_ || cell.y() >= rows_) {
    return std::nullopt;
  }
  const size_t index = static_cast<size_t>(cell.y()) * columns_ + static_cast<size_t>(cell.x());
  for (int k = cell_start_[index]; k < cell_start_[index + 1]; ++k) {
    if (const std::optional<double> height = heightWithin(triangles_[cell_triangles_[k]], xy)) {
      return height;
    }
  }
  return std::nullopt;
}

std::optional<double> TerrainSurface::lowestHeight() const {
  std::optional<double> lowest;
  for (const Triangle& triangle : triangles_) {
    for (const Eigen::Vector3d& corner : triangle) {
      lowest = std::min(lowest.value_or(corner.z()), corner.z());
    }
  }
  return lowest;
}

}  // namespace lineloc
