#include "db/loader/model_writer.h"

#include <fmt/format.h>

#include <unordered_map>

#include "db/citymodel/polygon_geometry.h"
#include "db/ewkb.h"

namespace lineloc::db {
namespace {

using citymodel::Building;
using citymodel::ExtractedLine;

constexpr const char* kNull = "\\N";

// COPY text format: backslash, tab, newline and carriage return escaped.
void appendEscaped(std::string& out, const std::string& text) {
  for (const char c : text) {
    switch (c) {
      case '\\':
        out.append("\\\\");
        break;
      case '\t':
        out.append("\\t");
        break;
      case '\n':
        out.append("\\n");
        break;
      case '\r':
        out.append("\\r");
        break;
      default:
        out.push_back(c);
    }
  }
}

void appendVector(std::string& out, const Eigen::Vector3d& v) {
  fmt::format_to(std::back_inserter(out), "{:.9g}\t{:.9g}\t{:.9g}\t", v.x(), v.y(), v.z());
}

bool isUnchanged(Connection& connection, const Site& site, const SourceRecord& source) {
  const Result stored = connection.execParams(
      "SELECT hash, options FROM source_file WHERE site_id = $1 AND name = $2",
      {std::to_string(site.id), source.name});
  return stored.rows() == 1 && stored.text(0, 0) == source.hash &&
         stored.text(0, 1) == source.options;
}

std::vector<int64_t> reserveBuildingIds(Connection& connection, size_t count) {
  const Result result =
      connection.execParams("SELECT nextval('building_id_seq') FROM generate_series(1, $1::int)",
                            {std::to_string(count)});
  std::vector<int64_t> ids(count);
  for (size_t i = 0; i < count; ++i) {
    ids[i] = std::stoll(result.text(static_cast<int>(i), 0));
  }
  return ids;
}

}  // namespace

WriteSummary writeModel(Connection& connection, const Site& site, const SourceRecord& source,
                        const std::vector<Building>& buildings,
                        const std::vector<std::vector<ExtractedLine>>& lines,
                        const std::function<void(size_t)>& progress) {
  connection.execParams("SELECT pg_advisory_xact_lock(hashtext($1))",
                        {fmt::format("lineloc-load {} {}", site.id, source.name)});
  WriteSummary summary;
  if (isUnchanged(connection, site, source)) {
    summary.unchanged = true;
    return summary;
  }
  const std::string site_id = std::to_string(site.id);
  connection.execParams("DELETE FROM building WHERE site_id = $1 AND source = $2",
                        {site_id, source.name});
  const std::vector<int64_t> ids = reserveBuildingIds(connection, buildings.size());
  std::unordered_map<std::string, int64_t> id_of;
  for (size_t i = 0; i < buildings.size(); ++i) {
    id_of.emplace(buildings[i].id, ids[i]);
  }
  {
    CopyIn copy(connection,
                "COPY building (id, site_id, parent_id, source, source_id, source_hash, "
                "object_type, lod, attributes) FROM STDIN");
    for (size_t i = 0; i < buildings.size(); ++i) {
      const Building& building = buildings[i];
      std::string& row = copy.buffer();
      const auto parent = id_of.find(building.parent_id);
      fmt::format_to(std::back_inserter(row), "{}\t{}\t{}\t", ids[i], site_id,
                     parent == id_of.end() ? kNull : std::to_string(parent->second));
      for (const std::string* text : {&source.name, &building.id, &source.hash, &building.type,
                                      &building.lod, &building.attributes_json}) {
        appendEscaped(row, *text);
        row.push_back(text == &building.attributes_json ? '\n' : '\t');
      }
      copy.flushIfFull();
    }
    copy.finish();
  }
  CopyIn faces(connection,
               "COPY face (site_id, building_id, ordinal, kind, normal_x, normal_y, normal_z, "
               "geom) FROM STDIN");
  for (size_t i = 0; i < buildings.size(); ++i) {
    const auto& building_faces = buildings[i].faces;
    for (size_t ordinal = 0; ordinal < building_faces.size(); ++ordinal) {
      std::string& row = faces.buffer();
      fmt::format_to(std::back_inserter(row), "{}\t{}\t{}\t{}\t", site_id, ids[i], ordinal,
                     static_cast<int>(building_faces[ordinal].kind));
      appendVector(row, citymodel::faceNormal(building_faces[ordinal]));
      appendHexPolygonZ(row, site.srid, building_faces[ordinal].rings);
      row.push_back('\n');
      ++summary.faces;
    }
    faces.flushIfFull();
  }
  faces.finish();
  CopyIn copy_lines(connection,
                    "COPY line (site_id, building_id, kind, face_a, face_b, normal_a_x, "
                    "normal_a_y, normal_a_z, normal_b_x, normal_b_y, normal_b_z, geom) FROM STDIN");
  for (size_t i = 0; i < buildings.size(); ++i) {
    for (const ExtractedLine& line : lines[i]) {
      std::string& row = copy_lines.buffer();
      fmt::format_to(std::back_inserter(row), "{}\t{}\t{}\t{}\t", site_id, ids[i],
                     static_cast<int>(line.kind), line.face_a);
      if (line.face_b >= 0) {
        fmt::format_to(std::back_inserter(row), "{}\t", line.face_b);
      } else {
        row.append("\\N\t");
      }
      appendVector(row, line.normal_a);
      if (line.face_b >= 0) {
        appendVector(row, line.normal_b);
      } else {
        row.append("\\N\t\\N\t\\N\t");
      }
      appendHexLineStringZ(row, site.srid, line.start, line.end);
      row.push_back('\n');
      ++summary.lines;
    }
    copy_lines.flushIfFull();
    if (progress) {
      progress(i + 1);
    }
  }
  copy_lines.finish();
  summary.buildings = static_cast<int>(buildings.size());
  connection.execParams(
      "INSERT INTO source_file (site_id, name, hash, options, buildings, faces, lines) "
      "VALUES ($1, $2, $3, $4, $5, $6, $7) ON CONFLICT (site_id, name) DO UPDATE SET "
      "hash = EXCLUDED.hash, options = EXCLUDED.options, buildings = EXCLUDED.buildings, "
      "faces = EXCLUDED.faces, lines = EXCLUDED.lines, loaded_at = now()",
      {site_id, source.name, source.hash, source.options, std::to_string(summary.buildings),
       std::to_string(summary.faces), std::to_string(summary.lines)});
  return summary;
}

}  // namespace lineloc::db
