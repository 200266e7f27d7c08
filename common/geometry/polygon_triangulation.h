// Triangulation of planar 3D polygons (building faces) by ear clipping in the
// polygon's own plane (Meisters, "Polygons have ears", 1975; O(n^2), which is
// fine for faces of tens of vertices). The plane normal is Newell's, so the
// method works for concave rings and slightly non-planar ones.
#pragma once

#include <Eigen/Core>
#include <array>
#include <vector>

namespace lineloc {

// `ring`: the outer ring of a simple polygon without the repeated closing
// vertex, in either orientation. Returns n - 2 index triples into `ring`
// (counter-clockwise about the Newell normal), or an empty list when the ring
// has fewer than 3 vertices or no area.
std::vector<std::array<int, 3>> triangulatePolygon(const std::vector<Eigen::Vector3d>& ring);

// Newell's normal of a ring: twice its area times its unit normal (right-hand
// rule over the vertex order); zero for an empty ring.
Eigen::Vector3d newellNormal(const std::vector<Eigen::Vector3d>& ring);

}  // namespace lineloc
