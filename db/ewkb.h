// PostGIS extended well-known binary (EWKB) for the two geometry types lineloc
// stores: LINESTRING Z and POLYGON Z with an SRID. Writing appends the
// binary form a binary COPY field takes; reading decodes the binary form a
// binary-result query returns (either byte order).
#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

namespace lineloc::db {

// Appends the EWKB of the segment a-b.
void appendEwkbLineStringZ(std::string& out, int srid, const Eigen::Vector3d& a,
                           const Eigen::Vector3d& b);

// Appends the EWKB of a polygon; rings are open (closed here by repeating
// the first vertex), rings[0] the exterior.
void appendEwkbPolygonZ(std::string& out, int srid,
                        const std::vector<std::vector<Eigen::Vector3d>>& rings);

// The points of a LINESTRING Z, or of every ring of a POLYGON Z (each ring
// closed, as stored). Nothing when the bytes are not such a geometry.
std::optional<std::vector<std::vector<Eigen::Vector3d>>> decodeEwkbZ(const char* bytes,
                                                                     size_t length);

}  // namespace lineloc::db
