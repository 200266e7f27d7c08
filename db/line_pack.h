// A building's lines packed into one bytea (table building_line_pack,
// migration 0003): the radius and view-frustum queries fetch one row per
// building near the robot and decode its records here, a copy and a byte swap
// per field, instead of one row with eleven columns and an EWKB geometry per
// line. The same bytes come from lineloc-load (appendLinePackRecord) and from
// SQL (line_pack_record over the line table).
//
// Record, big-endian, kLinePackRecordBytes long:
//   id int8 | kind int2 | face_a int4 | face_b int4 |
//   start xyz | end xyz | normal_a xyz | normal_b xyz  (float8)
// coordinates in the site CRS; faces -1 and normals zero when absent.
#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "db/citymodel/line_extraction.h"
#include "db/model_line_query.h"

namespace lineloc::db {

inline constexpr size_t kLinePackRecordBytes = 8 + 2 + 4 + 4 + 12 * 8;

// Appends the record of line `line_id` (`line` in site CRS coordinates).
void appendLinePackRecord(std::string& pack, int64_t line_id, const citymodel::ExtractedLine& line);

// Appends the lines of building `building_id`'s `pack` to `lines`, in world
// coordinates (site CRS minus `origin`). Throws DatabaseError naming the
// building when the pack is not whole records, a kind is unknown, or a
// coordinate or normal is not finite.
void decodeLinePack(std::string_view pack, int64_t building_id, const Eigen::Vector3d& origin,
                    std::vector<ModelLine>& lines);

}  // namespace lineloc::db
