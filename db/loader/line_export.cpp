#include "db/loader/line_export.h"

#include <fmt/format.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

namespace lineloc::db {
namespace {

constexpr const char* kKindNames[] = {"other", "vertical", "eave", "ridge", "ground"};
// Learnt lines follow the model's kinds in the export.
constexpr int kLearntKind = static_cast<int>(std::size(kKindNames));

struct StoredLine {
  std::string building_id = {};
  int kind = 0;
  Eigen::Vector3d start = Eigen::Vector3d::Zero();
  Eigen::Vector3d end = Eigen::Vector3d::Zero();
  // Learnt lines only.
  std::string status = {};
  int passes = 0;
};

std::vector<StoredLine> storedLines(Connection& connection, const Site& site) {
  const Result result = connection.execParams(
      "SELECT building_id, kind, ST_X(ST_StartPoint(geom)), ST_Y(ST_StartPoint(geom)), "
      "ST_Z(ST_StartPoint(geom)), ST_X(ST_EndPoint(geom)), ST_Y(ST_EndPoint(geom)), "
      "ST_Z(ST_EndPoint(geom)) FROM line WHERE site_id = $1 ORDER BY kind, id",
      {std::to_string(site.id)});
  std::vector<StoredLine> lines(result.rows());
  for (int row = 0; row < result.rows(); ++row) {
    const auto number = [&](int column) { return std::stod(result.text(row, column)); };
    lines[row] = {result.text(row, 0),
                  std::stoi(result.text(row, 1)),
                  {number(2), number(3), number(4)},
                  {number(5), number(6), number(7)}};
  }
  return lines;
}

// The learnt lines the filter takes, in the site's CRS.
std::vector<StoredLine> learntLines(Connection& connection, const Site& site,
                                    const EnrichmentFilter& filter) {
  std::vector<StoredLine> lines;
  for (const StoredEnrichmentLine& line : readEnrichment(connection, site, filter)) {
    lines.push_back({line.building_id ? std::to_string(*line.building_id) : std::string(),
                     kLearntKind, line.start_world + site.origin, line.end_world + site.origin,
                     toString(line.status), line.passes});
  }
  return lines;
}

std::string kindName(int kind) {
  if (kind == kLearntKind) {
    return "learnt";
  }
  return kind >= 0 && kind < kLearntKind ? kKindNames[kind] : "other";
}

void writeObj(std::ofstream& out, const Site& site, const std::vector<StoredLine>& lines) {
  out << fmt::format("# lineloc site '{}', EPSG:{}, coordinates minus origin ({}, {}, {})\n",
                     site.name, site.srid, site.origin.x(), site.origin.y(), site.origin.z());
  int current_kind = -1;
  int vertex = 0;
  for (const StoredLine& line : lines) {
    if (line.kind != current_kind) {
      current_kind = line.kind;
      out << "g " << kindName(line.kind) << '\n';
    }
    const Eigen::Vector3d a = line.start - site.origin;
    const Eigen::Vector3d b = line.end - site.origin;
    out << fmt::format("v {:.4f} {:.4f} {:.4f}\nv {:.4f} {:.4f} {:.4f}\nl {} {}\n", a.x(), a.y(),
                       a.z(), b.x(), b.y(), b.z(), vertex + 1, vertex + 2);
    vertex += 2;
  }
}

void writeGeoJson(std::ofstream& out, const Site& site, const std::vector<StoredLine>& lines) {
  nlohmann::json features = nlohmann::json::array();
  for (const StoredLine& line : lines) {
    nlohmann::json properties = {{"kind", kindName(line.kind)}, {"building_id", line.building_id}};
    if (line.kind == kLearntKind) {
      properties["status"] = line.status;
      properties["passes"] = line.passes;
    }
    features.push_back({{"type", "Feature"},
                        {"properties", properties},
                        {"geometry",
                         {{"type", "LineString"},
                          {"coordinates",
                           {{line.start.x(), line.start.y(), line.start.z()},
                            {line.end.x(), line.end.y(), line.end.z()}}}}}});
  }
  const nlohmann::json document = {
      {"type", "FeatureCollection"},
      {"crs",
       {{"type", "name"},
        {"properties", {{"name", fmt::format("urn:ogc:def:crs:EPSG::{}", site.srid)}}}}},
      {"features", features}};
  out << document.dump() << '\n';
}

}  // namespace

int exportLines(Connection& connection, const Site& site, const std::string& path,
                const std::optional<EnrichmentFilter>& learnt) {
  const std::string extension = std::filesystem::path(path).extension().string();
  if (extension != ".obj" && extension != ".geojson" && extension != ".json") {
    throw std::runtime_error(
        fmt::format("{}: unknown export format (expected .obj, .geojson or .json)", path));
  }
  std::ofstream out(path);
  if (!out) {
    throw std::runtime_error(fmt::format("{}: cannot write", path));
  }
  std::vector<StoredLine> lines = storedLines(connection, site);
  if (learnt) {
    const std::vector<StoredLine> more = learntLines(connection, site, *learnt);
    lines.insert(lines.end(), more.begin(), more.end());
  }
  if (extension == ".obj") {
    writeObj(out, site, lines);
  } else {
    writeGeoJson(out, site, lines);
  }
  if (!out.flush()) {
    throw std::runtime_error(fmt::format("{}: write failed", path));
  }
  return static_cast<int>(lines.size());
}

}  // namespace lineloc::db
