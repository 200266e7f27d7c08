// lineloc-load: loads city models (CityJSON, CityJSON Lines, OBJ, GeoJSON
// footprints) into a lineloc PostGIS database, or a synthetic city, and
// exports the stored lines for viewing (db/loader/load_job.h).
#include <unistd.h>

#include <iostream>
#include <memory>
#include <vector>

#include "common/config/program_options.h"
#include "common/progress/progress_meter.h"
#include "db/loader/load_job.h"

int main(int argc, char** argv) {
  lineloc::db::LoadJobConfig config;
  lineloc::ProgramOptions program(
      "lineloc-load", "Load city models into a lineloc database: buildings, faces, 3D lines");
  program.addPositional("files", config.files,
                        "City models: .json/.city.json (CityJSON 1.1/2.0), .jsonl (CityJSON "
                        "Lines), .obj (Wavefront, needs --city-model-crs), .geojson (footprints)");
  program.add("db", config.db, "libpq connection string of the database, as its writer role");
  program.add("site", config.site, "site to load into; created when new");
  program.add("city_model_crs", config.city_model_crs,
              "CRS of files that name none (EPSG:N); refused when neither gives one");
  program.add("site_crs", config.site_crs, "CRS of a new site (EPSG:N); default: the first file's");
  program.addFixedSize(
      "site_origin", config.site_origin, 3,
      "model coordinates x y z of a new site's origin; default: centre of the data");
  program.add("lod", config.lod,
              "level of detail to load (2.2, 1.2, 2...); default: highest present");
  program.addFlag("skip_invalid", config.skip_invalid,
                  "skip invalid objects (counted in the summary) instead of aborting the load");
  program.addFlag("dry_run", config.dry_run, "validate and report without writing");
  program.add("export_lines", config.export_lines,
              "after loading, write the site's lines to this .obj or .geojson file");
  program.add("export_enrichment", config.export_enrichment,
              "with --export-lines: the site's learnt lines of this status follow the model's "
              "(candidate, confirmed, retired or all; empty: none)");
  program.addFixedSize("obj_offset", config.obj_offset, 3,
                       "x y z added to OBJ vertices (OBJ files carry no georeference)");
  program.add("height_attribute", config.footprints.height_attribute,
              "GeoJSON property with the building height in metres");
  program.add("base_attribute", config.footprints.base_attribute,
              "GeoJSON property with the base height; default: the footprint's z, or 0");
  program.add("id_attribute", config.footprints.id_attribute,
              "GeoJSON property with the building id; default: the feature id");
  program.add("planarity_tolerance_m", config.validation.planarity_tolerance_m,
              "max distance of a face vertex from the face's plane");
  program.add("coplanar_angle_deg", config.coplanar_angle_deg,
              "edges between faces closer to coplanar than this are not lines");
  program.add("synthetic_buildings", config.synthetic_buildings,
              "load a synthetic city of this many buildings (for scale tests) instead of files");
  program.add("synthetic_seed", config.synthetic_seed, "random seed of the synthetic city");
  if (const auto exit_code = program.parse(argc, argv)) {
    return *exit_code;
  }
  try {
    std::unique_ptr<lineloc::ProgressMeter> meter;
    const auto progressFor = [&meter](const std::string& source) {
      meter =
          std::make_unique<lineloc::ProgressMeter>("writing " + source, "buildings", std::cerr,
                                                   lineloc::ProgressMeter::styleOf(STDERR_FILENO));
      return meter->callback();
    };
    lineloc::db::runLoadJob(config, std::cout, progressFor);
    return 0;
  } catch (const std::exception& error) {
    std::cerr << "lineloc-load: " << error.what() << '\n';
    return 1;
  }
}
