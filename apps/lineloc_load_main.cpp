// lineloc-load: loads city models (CityJSON, CityJSON Lines, OBJ, GeoJSON
// footprints) into a lineloc PostGIS database, or a synthetic city, and
// exports the stored lines for viewing.
#include <fmt/format.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <iostream>

#include "common/config/program_options.h"
#include "db/citymodel/synthetic_city.h"
#include "db/loader/line_export.h"
#include "db/loader/loader.h"
#include "db/migrations.h"
#include "db/site.h"

namespace {

using lineloc::db::LoadOptions;
using lineloc::db::LoadReport;

// A one-line progress bar on a terminal; nothing when stderr is redirected.
void showProgress(const std::string& source, size_t done, size_t total) {
  static const bool terminal = isatty(STDERR_FILENO) != 0;
  if (!terminal || total == 0 || (done % 256 != 0 && done != total)) {
    return;
  }
  constexpr int kWidth = 40;
  const int filled = static_cast<int>(kWidth * done / total);
  std::cerr << fmt::format("\r{} [{}{}] {}/{} buildings", source, std::string(filled, '#'),
                           std::string(kWidth - filled, '.'), done, total)
            << (done == total ? "\n" : "") << std::flush;
}

void printReport(const LoadReport& report, bool dry_run, double seconds) {
  const char* verb = dry_run ? "would load" : (report.unchanged ? "unchanged," : "loaded");
  std::cout << fmt::format(
      "{}: {} {} buildings, {} faces, {} lines, {} terrain triangles (LoD {}, EPSG:{} -> "
      "EPSG:{}) in {:.2f} s\n",
      report.source, verb, report.buildings, report.faces, report.lines, report.terrain_triangles,
      report.lod.empty() ? "-" : report.lod, report.source_epsg, report.site_epsg, seconds);
  for (const auto& [reason, count] : report.skipped.count_by_reason) {
    std::cout << fmt::format("  {} x {}\n", count, reason);
  }
  for (const std::string& message : report.skipped.messages) {
    if (message.find("not a building") == std::string::npos) {
      std::cout << "    " << message << '\n';
    }
  }
}

int parseEpsgOption(const std::string& value) {
  return value.empty() ? 0 : lineloc::citymodel::parseEpsgCode(value);
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::string> files;
  std::string conninfo = "host=127.0.0.1 port=55432 user=lineloc dbname=lineloc";
  std::string site = "default";
  std::string crs;
  std::string site_crs;
  std::vector<double> origin;
  std::vector<double> offset;
  std::string lod;
  bool skip_invalid = false;
  bool dry_run = false;
  std::string export_lines;
  int synthetic_buildings = 0;
  int synthetic_seed = 1;
  LoadOptions options;
  double coplanar_angle_deg = 10.0;

  lineloc::ProgramOptions program(
      "lineloc-load", "Load city models into a lineloc database: buildings, faces, 3D lines");
  program.app().add_option("files", files,
                           "City models: .json/.city.json (CityJSON 1.1/2.0), .jsonl (CityJSON "
                           "Lines), .obj (Wavefront, needs --crs), .geojson (footprints)");
  program.add("db", conninfo, "libpq connection string of the database (a writing role)");
  program.add("site", site, "site to load into; created when new");
  program.add("crs", crs, "CRS of files that name none (EPSG:N); refused when neither gives one");
  program.add("site_crs", site_crs, "CRS of a new site (EPSG:N); default: the first file's");
  program.addFixedSize("origin", origin, 3,
                       "origin x y z of a new site; default: centre of the data");
  program.add("lod", lod, "level of detail to load (2.2, 1.2, 2...); default: highest present");
  program.addFlag("skip_invalid", skip_invalid,
                  "skip invalid objects (counted in the summary) instead of aborting the load");
  program.addFlag("dry_run", dry_run, "validate and report without writing");
  program.add("export_lines", export_lines,
              "after loading, write the site's lines to this .obj or .geojson file");
  program.addFixedSize("offset", offset, 3,
                       "x y z added to OBJ vertices (OBJ files carry no georeference)");
  program.add("height_attribute", options.footprints.height_attribute,
              "GeoJSON property with the building height in metres");
  program.add("base_attribute", options.footprints.base_attribute,
              "GeoJSON property with the base height; default: the footprint's z, or 0");
  program.add("id_attribute", options.footprints.id_attribute,
              "GeoJSON property with the building id; default: the feature id");
  program.add("planarity_tolerance_m", options.validation.planarity_tolerance_m,
              "max distance of a face vertex from the face's plane");
  program.add("coplanar_angle_deg", coplanar_angle_deg,
              "edges between faces closer to coplanar than this are not lines");
  program.add("synthetic_buildings", synthetic_buildings,
              "load a synthetic city of this many buildings (for scale tests) instead of files");
  program.add("synthetic_seed", synthetic_seed, "random seed of the synthetic city");
  if (const auto exit_code = program.parse(argc, argv)) {
    return *exit_code;
  }
  try {
    options.site = site;
    options.dry_run = dry_run;
    options.read.lod = lod;
    options.read.invalid_objects = skip_invalid ? lineloc::citymodel::InvalidObjectPolicy::kSkip
                                                : lineloc::citymodel::InvalidObjectPolicy::kAbort;
    options.lines.coplanar_angle_rad = coplanar_angle_deg * M_PI / 180.0;
    if (const int epsg = parseEpsgOption(crs))
      options.file_epsg = epsg;
    if (const int epsg = parseEpsgOption(site_crs))
      options.site_epsg = epsg;
    if (!origin.empty()) {
      if (origin.size() != 3)
        throw std::invalid_argument("--origin needs 3 numbers: x y z");
      options.site_origin = Eigen::Vector3d(origin[0], origin[1], origin[2]);
    }
    if (!offset.empty()) {
      if (offset.size() != 3)
        throw std::invalid_argument("--offset needs 3 numbers: x y z");
      options.obj_offset = Eigen::Vector3d(offset[0], offset[1], offset[2]);
    }
    if (files.empty() && synthetic_buildings == 0 && export_lines.empty()) {
      throw std::invalid_argument(
          "nothing to do: give files, --synthetic-buildings or --export-lines");
    }
    std::unique_ptr<lineloc::db::Connection> connection;
    if (!dry_run || !export_lines.empty()) {
      connection = std::make_unique<lineloc::db::Connection>(conninfo);
      lineloc::db::applyMigrations(*connection, lineloc::db::embeddedMigrations());
    }
    for (const std::string& file : files) {
      const auto start = std::chrono::steady_clock::now();
      const LoadReport report = lineloc::db::loadFile(
          file, options, connection.get(),
          [&](size_t done, size_t total) { showProgress(file, done, total); });
      printReport(report, dry_run,
                  std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    }
    if (synthetic_buildings > 0) {
      const auto start = std::chrono::steady_clock::now();
      lineloc::citymodel::SyntheticCityOptions city;
      city.building_count = synthetic_buildings;
      city.seed = static_cast<uint32_t>(synthetic_seed);
      const std::string name = fmt::format("synthetic-{}-{}", synthetic_buildings, synthetic_seed);
      const lineloc::db::PreparedModel prepared = lineloc::db::prepareSynthetic(city, options);
      LoadReport report = lineloc::db::summarise(name, prepared);
      if (!dry_run) {
        report.unchanged = !lineloc::db::storeModel(
            *connection, options, {name, name, ""}, prepared,
            [&](size_t done, size_t total) { showProgress(name, done, total); });
      }
      printReport(report, dry_run,
                  std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    }
    if (!export_lines.empty()) {
      const auto target = lineloc::db::findSite(*connection, site);
      if (!target)
        throw std::invalid_argument(fmt::format("site '{}' is not in the database", site));
      const int written = lineloc::db::exportLines(*connection, *target, export_lines);
      std::cout << fmt::format("{}: wrote {} lines of site '{}'\n", export_lines, written, site);
    }
    return 0;
  } catch (const std::exception& error) {
    std::cerr << "lineloc-load: " << error.what() << '\n';
    return 1;
  }
}
