// lineloc-load's pipeline for one file: read it (format from its extension or
// content), resolve its CRS (the file's own, else the one given; refused when
// neither), transform it into the site's CRS, validate every face, extract the
// visible lines, then write it all in one transaction (or only report, for a
// dry run). Invalid objects abort the load, or are skipped and counted.
#pragma once

#include <Eigen/Core>
#include <functional>
#include <optional>
#include <string>

#include "common/progress/progress_meter.h"
#include "db/citymodel/city_model.h"
#include "db/citymodel/footprint_reader.h"
#include "db/citymodel/line_extraction.h"
#include "db/citymodel/polygon_geometry.h"
#include "db/citymodel/synthetic_city.h"
#include "db/connection.h"
#include "db/loader/model_writer.h"

namespace lineloc::db {

enum class InputFormat { kCityJson, kCityJsonLines, kWavefrontObj, kGeoJsonFootprints };

// From the extension (.jsonl, .obj, .geojson); a .json file is GeoJSON when it
// is a FeatureCollection, CityJSON otherwise. Throws std::invalid_argument.
InputFormat detectFormat(const std::string& path, std::string_view text);

struct LoadOptions {
  std::string site = "default";
  std::optional<int> file_epsg;                // for files that name no CRS
  std::optional<int> site_epsg;                // CRS of a new site; default: the file's
  std::optional<Eigen::Vector3d> site_origin;  // origin of a new site; default: centre of the data
  citymodel::ReadOptions read;
  citymodel::FootprintOptions footprints;
  Eigen::Vector3d obj_offset = Eigen::Vector3d::Zero();
  citymodel::FaceValidation validation;
  citymodel::LineExtractionOptions lines;
  // A file that names no CRS and is given none is kept in its own local
  // metric frame, untransformed (an object model for lineloc-track); false:
  // refused, as a site's database needs a CRS.
  bool local_frame_allowed = false;
  bool dry_run = false;
};

struct LoadReport {
  std::string source;
  std::string lod;
  int source_epsg = 0;
  int site_epsg = 0;
  bool unchanged = false;  // the same file was loaded before with the same options
  int buildings = 0;
  int faces = 0;
  int lines = 0;
  int terrain_triangles = 0;
  citymodel::SkippedObjects skipped;
};

// A model read, transformed, validated and with its lines: what would be written.
struct PreparedModel {
  citymodel::CityModel model;
  std::vector<std::vector<citymodel::ExtractedLine>> lines;
  // 0: a local frame (LoadOptions::local_frame_allowed).
  int source_epsg = 0;
};

// Reads, transforms into `target_epsg` (the source's own CRS when absent),
// validates and extracts lines. Throws citymodel::ModelError naming the file.
PreparedModel prepareModel(std::string_view text, const std::string& source_name,
                           InputFormat format, const LoadOptions& options,
                           std::optional<int> target_epsg);

// A synthetic city, validated and with its lines, in its own CRS.
PreparedModel prepareSynthetic(const citymodel::SyntheticCityOptions& city,
                               const LoadOptions& options);

// Counts of what a prepared model holds (and what was skipped), as a report.
LoadReport summarise(const std::string& source, const PreparedModel& prepared);

// Writes a prepared model (already in the site's CRS) as source `record` in
// one transaction; a new site gets the model's CRS and `options.site_origin`,
// or the centre of the data. Returns false when the source was unchanged.
bool storeModel(Connection& connection, const LoadOptions& options, const SourceRecord& record,
                const PreparedModel& prepared, const ProgressCallback& progress);

// The whole load of one file. `connection` may be null for a dry run.
// `progress(done, total)` reports buildings written.
LoadReport loadFile(const std::string& path, const LoadOptions& options, Connection* connection,
                    const ProgressCallback& progress);

// SHA-256 of `bytes`, lowercase hex.
std::string sha256Hex(std::string_view bytes);

}  // namespace lineloc::db
