#include "db/loader/loader.h"

#include <fmt/format.h>
#include <openssl/evp.h>

#include <Eigen/Geometry>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "db/citymodel/cityjson_reader.h"
#include "db/citymodel/crs_transform.h"
#include "db/citymodel/obj_reader.h"
#include "db/loader/model_writer.h"
#include "db/site.h"

namespace lineloc::db {
namespace {

using citymodel::CityModel;
using citymodel::ModelError;

std::string readFile(const std::string& path) {
  std::ifstream stream(path, std::ios::binary);
  if (!stream) {
    throw std::runtime_error(fmt::format("{}: cannot open", path));
  }
  std::ostringstream contents;
  contents << stream.rdbuf();
  return contents.str();
}

CityModel readModel(std::string_view text, const std::string& source, InputFormat format,
                    const LoadOptions& options) {
  switch (format) {
    case InputFormat::kCityJson:
      return citymodel::readCityJson(text, source, options.read);
    case InputFormat::kCityJsonLines:
      return citymodel::readCityJsonLines(text, source, options.read);
    case InputFormat::kWavefrontObj:
      return citymodel::readWavefrontObj(text, source, options.obj_offset, options.read);
    case InputFormat::kGeoJsonFootprints:
      return citymodel::readGeoJsonFootprints(text, source, options.footprints, options.read);
  }
  throw std::logic_error("unknown input format");
}

int resolveSourceCrs(const CityModel& model, const std::string& source,
                     const LoadOptions& options) {
  if (model.epsg && options.file_epsg && *model.epsg != *options.file_epsg) {
    throw ModelError(source, "", "conflicting CRS",
                     fmt::format("the file says EPSG:{}, --city-model-crs says EPSG:{}",
                                 *model.epsg, *options.file_epsg));
  }
  if (model.epsg) {
    return *model.epsg;
  }
  if (options.file_epsg) {
    return *options.file_epsg;
  }
  throw ModelError(
      source, "", "no CRS",
      "the file names no coordinate reference system; give it with --city-model-crs EPSG:N");
}

void validateAll(CityModel& model, const std::string& source, const LoadOptions& options) {
  std::vector<citymodel::Building> valid;
  valid.reserve(model.buildings.size());
  for (citymodel::Building& building : model.buildings) {
    try {
      citymodel::dropDegenerateFaces(building, options.validation, source, model.skipped);
      citymodel::triangulateNonPlanarFaces(building, options.validation, source, model.skipped);
      citymodel::validateFaces(building.faces, options.validation, source, building.id);
      valid.push_back(std::move(building));
    } catch (const ModelError& error) {
      citymodel::handleInvalidObject(error, options.read.invalid_objects, model.skipped);
    }
  }
  model.buildings = std::move(valid);
}

void validateAndExtract(PreparedModel& prepared, const std::string& source,
                        const LoadOptions& options) {
  validateAll(prepared.model, source, options);
  prepared.lines.reserve(prepared.model.buildings.size());
  for (const citymodel::Building& building : prepared.model.buildings) {
    prepared.lines.push_back(citymodel::extractLines(building.faces, options.lines));
  }
}

// The centre of the data's bounding box, rounded to 100 m, at height 0.
Eigen::Vector3d defaultOrigin(const CityModel& model) {
  Eigen::AlignedBox3d box;
  for (const citymodel::Building& building : model.buildings) {
    for (const citymodel::Face& face : building.faces) {
      for (const Eigen::Vector3d& point : face.rings.front()) {
        box.extend(point);
      }
    }
  }
  if (box.isEmpty()) {
    return Eigen::Vector3d::Zero();
  }
  const Eigen::Vector3d centre = box.center();
  return {std::round(centre.x() / 100.0) * 100.0, std::round(centre.y() / 100.0) * 100.0, 0.0};
}

std::string optionsRecord(const LoadOptions& options, const PreparedModel& prepared) {
  const std::string lod =
      prepared.model.buildings.empty() ? "" : prepared.model.buildings.front().lod;
  return fmt::format("lod={} skip_invalid={} planarity_m={} coplanar_rad={} offset={},{},{}", lod,
                     options.read.invalid_objects == citymodel::InvalidObjectPolicy::kSkip,
                     options.validation.planarity_tolerance_m, options.lines.coplanar_angle_rad,
                     options.obj_offset.x(), options.obj_offset.y(), options.obj_offset.z());
}

}  // namespace

InputFormat detectFormat(const std::string& path, std::string_view text) {
  const std::string extension = std::filesystem::path(path).extension().string();
  if (extension == ".jsonl")
    return InputFormat::kCityJsonLines;
  if (extension == ".obj")
    return InputFormat::kWavefrontObj;
  if (extension == ".geojson")
    return InputFormat::kGeoJsonFootprints;
  if (extension == ".json") {
    const bool feature_collection =
        text.substr(0, 4096).find("\"FeatureCollection\"") != std::string_view::npos;
    return feature_collection ? InputFormat::kGeoJsonFootprints : InputFormat::kCityJson;
  }
  throw std::invalid_argument(fmt::format(
      "{}: unknown format (expected .json, .city.json, .jsonl, .obj or .geojson)", path));
}

PreparedModel prepareModel(std::string_view text, const std::string& source_name,
                           InputFormat format, const LoadOptions& options,
                           std::optional<int> target_epsg) {
  PreparedModel prepared;
  prepared.model = readModel(text, source_name, format, options);
  const bool local_frame =
      options.local_frame_allowed && !prepared.model.epsg && !options.file_epsg;
  if (local_frame && target_epsg) {
    throw ModelError(
        source_name, "", "no CRS",
        fmt::format("a model in a local frame cannot be transformed into EPSG:{}", *target_epsg));
  }
  if (!local_frame) {
    prepared.source_epsg = resolveSourceCrs(prepared.model, source_name, options);
    std::unique_ptr<citymodel::CrsTransform> transform;
    try {
      transform = std::make_unique<citymodel::CrsTransform>(
          prepared.source_epsg, target_epsg.value_or(prepared.source_epsg));
    } catch (const std::invalid_argument& error) {
      throw ModelError(source_name, "", "unknown CRS", error.what());
    }
    transform->apply(prepared.model, source_name, options.read.invalid_objects);
  }
  validateAndExtract(prepared, source_name, options);
  return prepared;
}

PreparedModel prepareSynthetic(const citymodel::SyntheticCityOptions& city,
                               const LoadOptions& options) {
  PreparedModel prepared;
  prepared.model = citymodel::generateSyntheticCity(city);
  prepared.source_epsg = city.epsg;
  validateAndExtract(prepared, "synthetic city", options);
  return prepared;
}

LoadReport summarise(const std::string& source, const PreparedModel& prepared) {
  LoadReport report;
  report.source = source;
  report.source_epsg = prepared.source_epsg;
  report.site_epsg = prepared.model.epsg.value_or(prepared.source_epsg);
  report.skipped = prepared.model.skipped;
  report.buildings = static_cast<int>(prepared.model.buildings.size());
  report.terrain_triangles = static_cast<int>(prepared.model.terrain.size());
  for (const citymodel::Building& building : prepared.model.buildings) {
    if (report.lod.empty())
      report.lod = building.lod;
    report.faces += static_cast<int>(building.faces.size());
  }
  for (const auto& lines : prepared.lines) {
    report.lines += static_cast<int>(lines.size());
  }
  return report;
}

bool storeModel(Connection& connection, const LoadOptions& options, const SourceRecord& record,
                const PreparedModel& prepared, const ProgressCallback& progress) {
  const size_t total = prepared.model.buildings.size();
  const int srid = prepared.model.epsg.value_or(prepared.source_epsg);
  bool unchanged = false;
  inTransaction(connection, [&] {
    const std::optional<Site> existing = findSite(connection, options.site);
    const Site site = ensureSite(
        connection, options.site, srid,
        existing ? existing->origin : options.site_origin.value_or(defaultOrigin(prepared.model)));
    const WriteSummary written =
        writeModel(connection, site, record, prepared.model.buildings, prepared.lines,
                   prepared.model.terrain, [&](size_t done) {
                     if (progress)
                       progress(done, total);
                   });
    unchanged = written.unchanged;
  });
  return !unchanged;
}

LoadReport loadFile(const std::string& path, const LoadOptions& options, Connection* connection,
                    const ProgressCallback& progress) {
  const std::string text = readFile(path);
  const std::string source_name = std::filesystem::path(path).filename().string();
  std::optional<int> target_epsg = options.site_epsg;
  if (connection != nullptr) {
    if (const std::optional<Site> site = findSite(*connection, options.site)) {
      target_epsg = site->srid;
    }
  }
  const PreparedModel prepared =
      prepareModel(text, path, detectFormat(path, text), options, target_epsg);
  LoadReport report = summarise(source_name, prepared);
  if (options.dry_run || connection == nullptr) {
    return report;
  }
  const SourceRecord record{source_name, sha256Hex(text), optionsRecord(options, prepared)};
  report.unchanged = !storeModel(*connection, options, record, prepared, progress);
  return report;
}

std::string sha256Hex(std::string_view bytes) {
  unsigned char digest[EVP_MAX_MD_SIZE];
  unsigned int length = 0;
  if (EVP_Digest(bytes.data(), bytes.size(), digest, &length, EVP_sha256(), nullptr) != 1) {
    throw std::runtime_error("SHA-256 failed");
  }
  std::string hex;
  for (unsigned int i = 0; i < length; ++i) {
    fmt::format_to(std::back_inserter(hex), "{:02x}", digest[i]);
  }
  return hex;
}

}  // namespace lineloc::db
