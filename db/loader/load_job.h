// One run of lineloc-load: city model files, or a synthetic city for scale
// tests, loaded into one site of the database, a summary printed for each as
// it completes, then, when asked, the site's lines exported for viewing. The
// options are the program's, as given; loadOptionsOf checks and converts them.
#pragma once

#include <iosfwd>
#include <string>
#include <vector>

#include "common/progress/progress_meter.h"
#include "db/loader/loader.h"

namespace lineloc::db {

struct LoadJobConfig {
  std::vector<std::string> files;
  // libpq connection string of a role that may write rows (the writer role).
  std::string db = "host=127.0.0.1 port=55432 user=lineloc_writer dbname=lineloc";
  std::string site = "default";
  // "EPSG:N" of files that name no CRS; empty: each file's own.
  std::string city_model_crs;
  // "EPSG:N" of a new site; empty: the first file's.
  std::string site_crs;
  // Model coordinates x y z of a new site's origin; empty: the centre of the data.
  std::vector<double> site_origin;
  // x y z added to OBJ vertices, which carry no georeference; empty: none.
  std::vector<double> obj_offset;
  std::string lod;
  bool skip_invalid = false;
  bool dry_run = false;
  // .obj or .geojson file the site's lines are written to after loading.
  std::string export_lines;
  // With export_lines: the site's learnt lines of this status (candidate,
  // confirmed, retired, or all) follow the model's; empty: none.
  std::string export_enrichment;
  int synthetic_buildings = 0;
  int synthetic_seed = 1;
  double coplanar_angle_deg = 10.0;
  // GeoJSON attributes and face validation, used as they are.
  citymodel::FootprintOptions footprints;
  citymodel::FaceValidation validation;
};

// The loader's options. Throws std::invalid_argument naming the option that is
// malformed (a CRS that is no EPSG code, an origin or offset not of 3 numbers).
LoadOptions loadOptionsOf(const LoadJobConfig& config);

// Runs the job: connects (unless it is a dry run that exports nothing),
// checks the schema is migrated, loads each file, then the synthetic city,
// then exports.
// Writes one summary per source and one line per export to `out`;
// `progressFor(source)` gives the progress of the buildings written for each
// source. Returns the sources' reports. Throws std::invalid_argument when there
// is nothing to do or the site to export is unknown; the loader's errors
// otherwise, naming the file.
std::vector<LoadReport> runLoadJob(
    const LoadJobConfig& config, std::ostream& out,
    const std::function<ProgressCallback(const std::string& source)>& progressFor);

// A source's summary: what was (or would be) loaded, its CRS, the time it took
// and, for every kind of object skipped, the count and each message.
std::string describeLoad(const LoadReport& report, bool dry_run, double seconds);

}  // namespace lineloc::db
