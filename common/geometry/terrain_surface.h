// The height of a terrain given as triangles (a TIN, CityJSON TINRelief) at a
// point of the ground plane: z = sum_i b_i z_i over the corners of the
// triangle whose ground projection holds (x, y), with (b_0, b_1, b_2) the
// point's barycentric coordinates in that projection. Triangles are found
// through a uniform grid of cells over their bounding boxes, so a query
// costs the few triangles of one cell whatever the terrain's size.
#pragma once

#include <Eigen/Core>
#include <array>
#include <optional>
#include <vector>

namespace lineloc {

class TerrainSurface {
 public:
  using Triangle = std::array<Eigen::Vector3d, 3>;

  // `cell_size_m`: side of the grid's cells, about a triangle's size (larger
  // where the terrain's extent would otherwise need more than four cells per
  // triangle). Throws std::invalid_argument for a non-positive cell size, a
  // non-finite corner or an extent beyond the range of a double.
  explicit TerrainSurface(std::vector<Triangle> triangles, double cell_size_m = 10.0);

  // nullopt where no triangle lies under (x, y), and for an empty terrain.
  std::optional<double> heightAt(const Eigen::Vector2d& xy) const;

  bool empty() const { return triangles_.empty(); }
  // The lowest corner of any triangle; nullopt for an empty terrain.
  std::optional<double> lowestHeight() const;

 private:
  std::vector<Triangle> triangles_;
  double cell_size_m_;
  Eigen::Vector2d grid_origin_ = Eigen::Vector2d::Zero();
  int columns_ = 0;
  int rows_ = 0;
  // Triangle indices of cell (column, row) in cell_triangles_[cell_start_[row * columns_ +
  // column] .. cell_start_[... + 1]).
  std::vector<int> cell_start_;
  std::vector<int> cell_triangles_;
};

}  // namespace lineloc
