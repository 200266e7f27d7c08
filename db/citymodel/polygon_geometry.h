// Plane geometry of a face: its area-weighted normal by Newell's method
// (Sutherland, Sproull & Schumacker 1974; n = sum_i (v_i - v_{i+1}) x ... , i.e.
// n_x = sum (y_i - y_j)(z_i + z_j) and cyclic, which is 2 A times the unit normal
// for a planar ring), its semantic kind from the normal when the source gives
// none, and the checks that make a polygon usable: finite, non-degenerate, planar.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "db/citymodel/city_model.h"

namespace lineloc::citymodel {

// The face's unit normal from its exterior ring; zero when the ring has no area.
Eigen::Vector3d faceNormal(const Face& face);

// Wall when the normal is within 10 degrees of horizontal (|n_z| < sin 10°),
// roof when it points up, ground when it points down, other when it is zero.
SurfaceKind surfaceKindFromNormal(const Eigen::Vector3d& unit_normal);

struct FaceValidation {
  // Smaller faces are degenerate: collinear vertices. Real models hold slivers of
  // 1e-7 m² (a triangle of 1 mm-quantised vertices), which are valid.
  double min_area_m2 = 1e-9;
  double planarity_tolerance_m = 0.05;  // max distance of a vertex from the face's plane
};

// True when the face has collapsed: a ring with fewer than 3 distinct vertices,
// or an exterior ring with less than the minimum area.
bool isDegenerate(const Face& face, const FaceValidation& validation);

// Removes collapsed faces (real models carry them: a triangle whose vertices
// fell onto one another when quantised), recording each in `skipped` as
// "degenerate face dropped". Throws ModelError when no face is left.
void dropDegenerateFaces(Building& building, const FaceValidation& validation,
                         const std::string& source, SkippedObjects& skipped);

// Replaces each face whose vertices lie farther than the planarity tolerance
// from its plane (real models carry roofs and grounds bent by tens of
// centimetres) by the triangles of its ear-clipping triangulation, which are
// planar and keep its outline and kind; the line extraction drops the diagonals
// between nearly coplanar triangles. A non-planar face with holes is dropped.
// Each is recorded in `skipped` ("non-planar face triangulated" or "... dropped").
// Call after dropDegenerateFaces.
void triangulateNonPlanarFaces(Building& building, const FaceValidation& validation,
                               const std::string& source, SkippedObjects& skipped);

// Throws ModelError naming `source` and `object_id` when a face has a
// non-finite coordinate, fewer than 3 distinct vertices, no area, or a vertex
// farther than the tolerance from its plane.
void validateFaces(const std::vector<Face>& faces, const FaceValidation& validation,
                   const std::string& source, const std::string& object_id);

}  // namespace lineloc::citymodel
