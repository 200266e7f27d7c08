#include "db/loader/model_writer.h"

#include <fmt/format.h>

#include <algorithm>
#include <unordered_map>

#include "db/binary_copy.h"
#include "db/citymodel/polygon_geometry.h"
#include "db/ewkb.h"
#include "db/line_pack.h"

namespace lineloc::db {
namespace {

using citymodel::Building;
using citymodel::ExtractedLine;

constexpr char kJsonbVersion = 1;

bool isUnchanged(Connection& connection, const Site& site, const SourceRecord& source) {
  const Result stored = connection.execParams(
      "SELECT hash, options FROM source_file WHERE site_id = $1 AND name = $2",
      {std::to_string(site.id), source.name});
  return stored.rows() == 1 && stored.text(0, 0) == source.hash &&
         stored.text(0, 1) == source.options;
}

// `count` fresh values of `sequence`, ascending.
std::vector<int64_t> reserveIds(Connection& connection, const std::string& sequence, size_t count) {
  const Result result = connection.execParams(
      fmt::format("SELECT nextval('{}') FROM generate_series(1, $1::int)", sequence),
      {std::to_string(count)});
  std::vector<int64_t> ids(count);
  for (size_t i = 0; i < count; ++i) {
    ids[i] = std::stoll(result.text(static_cast<int>(i), 0));
  }
  std::sort(ids.begin(), ids.end());
  return ids;
}

void copyVector(BinaryCopyIn& copy, const Eigen::Vector3d& v) {
  copy.value(v.x());
  copy.value(v.y());
  copy.value(v.z());
}

void copyBuildings(Connection& connection, const Site& site, const SourceRecord& source,
                   const std::vector<Building>& buildings, const std::vector<int64_t>& ids) {
  std::unordered_map<std::string, int64_t> id_of;
  for (size_t i = 0; i < buildings.size(); ++i) {
    id_of.emplace(buildings[i].id, ids[i]);
  }
  BinaryCopyIn copy(connection,
                    "building (id, site_id, parent_id, source, source_id, source_hash, "
                    "object_type, lod, attributes)");
  for (size_t i = 0; i < buildings.size(); ++i) {
    const Building& building = buildings[i];
    copy.beginRow(9);
    copy.value(ids[i]);
    copy.value<int32_t>(site.id);
    if (const auto parent = id_of.find(building.parent_id); parent != id_of.end()) {
      copy.value(parent->second);
    } else {
      copy.null();
    }
    for (const std::string* text :
         {&source.name, &building.id, &source.hash, &building.type, &building.lod}) {
      copy.bytes(*text);
    }
    copy.field([&](std::string& out) {
      out.push_back(kJsonbVersion);
      out.append(building.attributes_json);
    });
  }
  copy.finish();
}

int copyFaces(Connection& connection, const Site& site, const std::vector<Building>& buildings,
              const std::vector<int64_t>& ids) {
  BinaryCopyIn copy(connection,
                    "face (site_id, building_id, ordinal, kind, normal_x, normal_y, normal_z, "
                    "geom)");
  int faces = 0;
  for (size_t i = 0; i < buildings.size(); ++i) {
    const auto& building_faces = buildings[i].faces;
    for (size_t ordinal = 0; ordinal < building_faces.size(); ++ordinal) {
      copy.beginRow(8);
      copy.value<int32_t>(site.id);
      copy.value(ids[i]);
      copy.value(static_cast<int32_t>(ordinal));
      copy.value(static_cast<int16_t>(building_faces[ordinal].kind));
      copyVector(copy, citymodel::faceNormal(building_faces[ordinal]));
      copy.field([&](std::string& out) {
        appendEwkbPolygonZ(out, site.srid, building_faces[ordinal].rings);
      });
      ++faces;
    }
  }
  copy.finish();
  return faces;
}

// One pack per building with lines (migration 0003; the trigger that would
// derive them is told they are written here), line ids from `line_ids` in order.
void copyLinePacks(Connection& connection, const Site& site,
                   const std::vector<std::vector<ExtractedLine>>& lines,
                   const std::vector<int64_t>& building_ids, const std::vector<int64_t>& line_ids) {
  BinaryCopyIn copy(connection, "building_line_pack (building_id, site_id, bounds, lines)");
  size_t next_id = 0;
  std::string pack;
  for (size_t i = 0; i < lines.size(); ++i) {
    if (lines[i].empty()) {
      continue;
    }
    Eigen::AlignedBox2d bounds;
    pack.clear();
    for (const ExtractedLine& line : lines[i]) {
      appendLinePackRecord(pack, line_ids[next_id++], line);
      bounds.extend(line.start.head<2>());
      bounds.extend(line.end.head<2>());
    }
    copy.beginRow(4);
    copy.value(building_ids[i]);
    copy.value<int32_t>(site.id);
    copy.field([&](std::string& out) {
      for (const double corner :
           {bounds.max().x(), bounds.max().y(), bounds.min().x(), bounds.min().y()}) {
        appendBigEndian(out, corner);
      }
    });
    copy.bytes(pack);
  }
  copy.finish();
}

// The lines, with ids from `line_ids` in order; returns how many.
int copyLines(Connection& connection, const Site& site,
              const std::vector<std::vector<ExtractedLine>>& lines,
              const std::vector<int64_t>& building_ids, const std::vector<int64_t>& line_ids,
              const std::function<void(size_t)>& progress) {
  BinaryCopyIn copy(connection,
                    "line (id, site_id, building_id, kind, face_a, face_b, normal_a_x, "
                    "normal_a_y, normal_a_z, normal_b_x, normal_b_y, normal_b_z, geom)");
  size_t next_id = 0;
  for (size_t i = 0; i < lines.size(); ++i) {
    for (const ExtractedLine& line : lines[i]) {
      copy.beginRow(13);
      copy.value(line_ids[next_id++]);
      copy.value<int32_t>(site.id);
      copy.value(building_ids[i]);
      copy.value(static_cast<int16_t>(line.kind));
      copy.value<int32_t>(line.face_a);
      const bool two_faces = line.face_b >= 0;
      if (two_faces) {
        copy.value<int32_t>(line.face_b);
      } else {
        copy.null();
      }
      copyVector(copy, line.normal_a);
      if (two_faces) {
        copyVector(copy, line.normal_b);
      } else {
        copy.null();
        copy.null();
        copy.null();
      }
      copy.field(
          [&](std::string& out) { appendEwkbLineStringZ(out, site.srid, line.start, line.end); });
    }
    if (progress) {
      progress(i + 1);
    }
  }
  copy.finish();
  return static_cast<int>(next_id);
}

int copyTerrain(Connection& connection, const Site& site, const SourceRecord& source,
                const std::vector<citymodel::TerrainTriangle>& terrain) {
  BinaryCopyIn copy(connection, "terrain_triangle (site_id, source, geom)");
  for (const citymodel::TerrainTriangle& triangle : terrain) {
    copy.beginRow(3);
    copy.value<int32_t>(site.id);
    copy.bytes(source.name);
    copy.field([&](std::string& out) {
      appendEwkbPolygonZ(out, site.srid, {{triangle[0], triangle[1], triangle[2]}});
    });
  }
  copy.finish();
  return static_cast<int>(terrain.size());
}

}  // namespace

WriteSummary writeModel(Connection& connection, const Site& site, const SourceRecord& source,
                        const std::vector<Building>& buildings,
                        const std::vector<std::vector<ExtractedLine>>& lines,
                        const std::vector<citymodel::TerrainTriangle>& terrain,
                        const std::function<void(size_t)>& progress) {
  connection.execParams("SELECT pg_advisory_xact_lock(hashtext($1))",
                        {fmt::format("lineloc-load {} {}", site.id, source.name)});
  WriteSummary summary;
  if (isUnchanged(connection, site, source)) {
    summary.unchanged = true;
    return summary;
  }
  connection.exec("SELECT set_config('lineloc.line_packs_written', 'on', true)");
  const std::string site_id = std::to_string(site.id);
  connection.execParams("DELETE FROM building WHERE site_id = $1 AND source = $2",
                        {site_id, source.name});
  connection.execParams("DELETE FROM terrain_triangle WHERE site_id = $1 AND source = $2",
                        {site_id, source.name});
  size_t line_count = 0;
  for (const auto& building_lines : lines) {
    line_count += building_lines.size();
  }
  const std::vector<int64_t> building_ids =
      reserveIds(connection, "building_id_seq", buildings.size());
  const std::vector<int64_t> line_ids = reserveIds(connection, "line_id_seq", line_count);
  copyBuildings(connection, site, source, buildings, building_ids);
  summary.faces = copyFaces(connection, site, buildings, building_ids);
  copyLinePacks(connection, site, lines, building_ids, line_ids);
  summary.lines = copyLines(connection, site, lines, building_ids, line_ids, progress);
  summary.terrain_triangles = copyTerrain(connection, site, source, terrain);
  summary.buildings = static_cast<int>(buildings.size());
  connection.execParams(
      "INSERT INTO source_file (site_id, name, hash, options, buildings, faces, lines, "
      "terrain_triangles) VALUES ($1, $2, $3, $4, $5, $6, $7, $8) ON CONFLICT (site_id, name) "
      "DO UPDATE SET hash = EXCLUDED.hash, options = EXCLUDED.options, buildings = "
      "EXCLUDED.buildings, faces = EXCLUDED.faces, lines = EXCLUDED.lines, terrain_triangles = "
      "EXCLUDED.terrain_triangles, loaded_at = now()",
      {site_id, source.name, source.hash, source.options, std::to_string(summary.buildings),
       std::to_string(summary.faces), std::to_string(summary.lines),
       std::to_string(summary.terrain_triangles)});
  return summary;
}

}  // namespace lineloc::db
