#include "db/loader/load_job.h"

#include <fmt/format.h>

#include <chrono>
#include <memory>
#include <numbers>
#include <ostream>
#include <stdexcept>

#include "common/config/option_values.h"
#include "db/citymodel/synthetic_city.h"
#include "db/loader/line_export.h"
#include "db/migrations.h"
#include "db/site.h"

namespace lineloc::db {
namespace {

std::optional<int> epsgOf(const std::string& value) {
  if (value.empty()) {
    return std::nullopt;
  }
  return citymodel::parseEpsgCode(value);
}

double secondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

LoadOptions loadOptionsOf(const LoadJobConfig& config) {
  LoadOptions options;
  options.site = config.site;
  options.dry_run = config.dry_run;
  options.read.lod = config.lod;
  options.read.invalid_objects = config.skip_invalid ? citymodel::InvalidObjectPolicy::kSkip
                                                     : citymodel::InvalidObjectPolicy::kAbort;
  options.footprints = config.footprints;
  options.validation = config.validation;
  options.lines.coplanar_angle_rad = config.coplanar_angle_deg * std::numbers::pi / 180.0;
  options.file_epsg = epsgOf(config.city_model_crs);
  options.site_epsg = epsgOf(config.site_crs);
  options.site_origin = pointOption(config.site_origin, "site_origin");
  options.obj_offset =
      pointOption(config.obj_offset, "obj_offset").value_or(Eigen::Vector3d::Zero());
  return options;
}

std::string describeLoad(const LoadReport& report, bool dry_run, double seconds) {
  const char* verb = dry_run ? "would load" : (report.unchanged ? "unchanged," : "loaded");
  std::string text = fmt::format(
      "{}: {} {} buildings, {} faces, {} lines, {} terrain triangles (LoD {}, EPSG:{} -> "
      "EPSG:{}) in {:.2f} s\n",
      report.source, verb, report.buildings, report.faces, report.lines, report.terrain_triangles,
      report.lod.empty() ? "-" : report.lod, report.source_epsg, report.site_epsg, seconds);
  for (const auto& [reason, count] : report.skipped.count_by_reason) {
    text += fmt::format("  {} x {}\n", count, reason);
  }
  for (const std::string& message : report.skipped.messages) {
    if (message.find("not a building") == std::string::npos) {
      text += fmt::format("    {}\n", message);
    }
  }
  return text;
}

std::vector<LoadReport> runLoadJob(
    const LoadJobConfig& config, std::ostream& out,
    const std::function<ProgressCallback(const std::string& source)>& progressFor) {
  const LoadOptions options = loadOptionsOf(config);
  if (config.files.empty() && config.synthetic_buildings == 0 && config.export_lines.empty()) {
    throw std::invalid_argument(
        "nothing to do: give city model files, --synthetic-buildings or --export-lines");
  }
  std::unique_ptr<Connection> connection;
  if (!config.dry_run || !config.export_lines.empty()) {
    connection = std::make_unique<Connection>(config.db);
    requireMigrated(*connection, embeddedMigrations());
  }
  std::vector<LoadReport> reports;
  for (const std::string& file : config.files) {
    const auto start = std::chrono::steady_clock::now();
    reports.push_back(loadFile(file, options, connection.get(), progressFor(file)));
    out << describeLoad(reports.back(), config.dry_run, secondsSince(start)) << std::flush;
  }
  if (config.synthetic_buildings > 0) {
    const auto start = std::chrono::steady_clock::now();
    citymodel::SyntheticCityOptions city;
    city.building_count = config.synthetic_buildings;
    city.seed = static_cast<uint32_t>(config.synthetic_seed);
    const std::string name =
        fmt::format("synthetic-{}-{}", config.synthetic_buildings, config.synthetic_seed);
    const PreparedModel prepared = prepareSynthetic(city, options);
    LoadReport report = summarise(name, prepared);
    if (!config.dry_run) {
      report.unchanged =
          !storeModel(*connection, options, {name, name, ""}, prepared, progressFor(name));
    }
    reports.push_back(report);
    out << describeLoad(report, config.dry_run, secondsSince(start)) << std::flush;
  }
  if (!config.export_lines.empty()) {
    const auto target = findSite(*connection, config.site);
    if (!target) {
      throw std::invalid_argument(fmt::format("site '{}' is not in the database", config.site));
    }
    std::optional<EnrichmentFilter> learnt;
    if (!config.export_enrichment.empty()) {
      learnt.emplace();
      if (config.export_enrichment != "all") {
        learnt->status = parseEnrichmentStatus(config.export_enrichment);
      }
    }
    const int written = exportLines(*connection, *target, config.export_lines, learnt);
    out << fmt::format("{}: wrote {} lines of site '{}'\n", config.export_lines, written,
                       config.site);
  }
  return reports;
}

}  // namespace lineloc::db
