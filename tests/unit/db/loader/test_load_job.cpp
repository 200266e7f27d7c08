// lineloc-load's job: the program's options checked and converted, a dry run
// without a database, and a load, an export and a reload on a real PostGIS
// server.
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <numbers>
#include <sstream>

#include "db/loader/load_job.h"
#include "tests/support/test_database.h"

namespace lineloc::db {
namespace {

namespace fs = std::filesystem;

std::string delftModel() {
  return (fs::path(LINELOC_SOURCE_DIR) / "data" / "citymodels" / "delft.json").string();
}

ProgressCallback noProgress(const std::string&) {
  return nullptr;
}

std::string errorOf(const LoadJobConfig& config) {
  try {
    loadOptionsOf(config);
  } catch (const std::invalid_argument& error) {
    return error.what();
  }
  return "";
}

TEST(LoadJob, ConvertsTheProgramsOptions) {
  LoadJobConfig config;
  config.site = "delft";
  config.city_model_crs = "EPSG:7415";
  config.site_crs = "EPSG:28992";
  config.site_origin = {84900.0, 447600.0, 0.0};
  config.obj_offset = {1.0, 2.0, 3.0};
  config.skip_invalid = true;
  config.coplanar_angle_deg = 30.0;
  const LoadOptions options = loadOptionsOf(config);
  EXPECT_EQ(options.site, "delft");
  EXPECT_EQ(options.file_epsg, std::optional<int>(7415));
  EXPECT_EQ(options.site_epsg, std::optional<int>(28992));
  ASSERT_TRUE(options.site_origin.has_value());
  EXPECT_EQ(*options.site_origin, Eigen::Vector3d(84900.0, 447600.0, 0.0));
  EXPECT_EQ(options.obj_offset, Eigen::Vector3d(1.0, 2.0, 3.0));
  EXPECT_EQ(options.read.invalid_objects, citymodel::InvalidObjectPolicy::kSkip);
  EXPECT_DOUBLE_EQ(options.lines.coplanar_angle_rad, std::numbers::pi / 6.0);

  const LoadOptions defaults = loadOptionsOf(LoadJobConfig{});
  EXPECT_FALSE(defaults.file_epsg.has_value());
  EXPECT_FALSE(defaults.site_origin.has_value());
  EXPECT_EQ(defaults.read.invalid_objects, citymodel::InvalidObjectPolicy::kAbort);
}

TEST(LoadJob, RefusesMalformedOptionsNamingThem) {
  LoadJobConfig config;
  config.site_origin = {84900.0, 447600.0};
  EXPECT_NE(errorOf(config).find("site_origin"), std::string::npos) << errorOf(config);
  config = {};
  config.obj_offset = {1.0};
  EXPECT_NE(errorOf(config).find("obj_offset"), std::string::npos) << errorOf(config);
  config = {};
  config.city_model_crs = "RD New";
  EXPECT_ANY_THROW(loadOptionsOf(config));
  std::ostringstream out;
  EXPECT_THROW(runLoadJob(LoadJobConfig{}, out, noProgress), std::invalid_argument);
}

TEST(LoadJob, ADryRunNeedsNoDatabase) {
  LoadJobConfig config;
  config.files = {delftModel()};
  config.dry_run = true;
  config.db = "host=/nonexistent";
  std::ostringstream out;
  const std::vector<LoadReport> reports = runLoadJob(config, out, noProgress);
  ASSERT_EQ(reports.size(), 1u);
  EXPECT_GT(reports[0].buildings, 100);
  EXPECT_GT(reports[0].lines, reports[0].buildings);
  EXPECT_NE(out.str().find(fmt::format("would load {} buildings", reports[0].buildings)),
            std::string::npos)
      << out.str();
}

TEST(LoadJob, LoadsExportsAndReloadsUnchanged) {
  test::TestDatabase database("load_job");
  const fs::path exported =
      fs::temp_directory_path() / fmt::format("load_job_{}.geojson", getpid());
  LoadJobConfig config;
  config.db = database.conninfo(test::DatabaseRole::kWriter);
  config.site = "delft";
  config.site_origin = {84900.0, 447600.0, 0.0};
  config.files = {delftModel()};
  config.export_lines = exported.string();
  size_t last_done = 0;
  size_t last_total = 0;
  const auto progressFor = [&](const std::string& source) -> ProgressCallback {
    EXPECT_EQ(source, delftModel());
    return [&](size_t done, size_t total) {
      EXPECT_GE(done, last_done);
      last_done = done;
      last_total = total;
    };
  };
  std::ostringstream out;
  const std::vector<LoadReport> loaded = runLoadJob(config, out, progressFor);
  ASSERT_EQ(loaded.size(), 1u);
  EXPECT_FALSE(loaded[0].unchanged);
  EXPECT_EQ(last_total, static_cast<size_t>(loaded[0].buildings));
  EXPECT_EQ(last_done, last_total);
  EXPECT_NE(out.str().find(fmt::format("wrote {} lines of site 'delft'", loaded[0].lines)),
            std::string::npos)
      << out.str();
  EXPECT_TRUE(fs::exists(exported));

  std::ostringstream again;
  const std::vector<LoadReport> reloaded = runLoadJob(config, again, progressFor);
  EXPECT_TRUE(reloaded[0].unchanged);
  EXPECT_NE(again.str().find("unchanged,"), std::string::npos) << again.str();
  fs::remove(exported);

  config.files.clear();
  config.site = "nowhere";
  try {
    runLoadJob(config, out, progressFor);
    FAIL() << "exported a site that does not exist";
  } catch (const std::invalid_argument& error) {
    EXPECT_NE(std::string(error.what()).find("'nowhere'"), std::string::npos) << error.what();
  }
}

}  // namespace
}  // namespace lineloc::db
