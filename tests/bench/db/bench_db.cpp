// Benchmarks of the building database (paper §3.1: lines near the robot,
// fast), on a PostGIS server named by LINELOC_BENCH_DB (a libpq connection
// string; default the deploy/pg.sh cluster as its owner role, database
// lineloc_bench, which is created and filled with a 100,000-building synthetic
// city on first run; a streaming replica of a cluster that holds it, named by
// LINELOC_BENCH_DB, is queried as it is, with --benchmark_filter=LinesWithin).
// With LINELOC_BENCH_CITY_MODEL set, the queries run on that city model
// instead (loaded on first run as site LINELOC_BENCH_SITE, default "city"),
// around random positions within its lines' extent:
//  - the 150 m query around random street positions: ModelLineQuery (line
//    packs under a 2D GiST box, binary bytea, exact distance in C++) beside a
//    plain ST_3DDWithin query decoded from text (with the n-D index it needs,
//    which lineloc's schema does not have), each query's latency recorded so
//    the median and 99th percentile are reported, and their ratio;
//  - load throughput, LoD2 buildings per second through the whole pipeline
//    (generate, validate, extract lines, binary COPY, commit) beside the
//    per-row INSERTs a user would write, into database <name>_load (created on
//    first run, so the baseline's index does not tax the loads). Besides
//    wall-clock rates, buildings per CPU second of the loader and its server
//    backend together: the rate on one core, whatever else the machine runs.
#include <benchmark/benchmark.h>
#include <fmt/format.h>
#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <fstream>
#include <map>
#include <random>

#include "db/citymodel/polygon_geometry.h"
#include "db/loader/loader.h"
#include "db/migrations.h"
#include "db/model_line_query.h"
#include "db/site.h"
#include "tests/support/test_database.h"

namespace {

using lineloc::db::Connection;

constexpr int kCityBuildings = 100000;
constexpr double kRadius_m = 150.0;
constexpr int kQueries = 400;
constexpr int kLoadBuildings = 2000;
constexpr int kNaiveLoadBuildings = 200;

// Creates database `name` in the cluster `server` connects to, when missing.
void createDatabaseIfMissing(Connection& server, const std::string& name) {
  if (server.execParams("SELECT 1 FROM pg_database WHERE datname = $1", {name}).rows() == 0) {
    server.exec(fmt::format("CREATE DATABASE {}", name));
  }
}

std::string benchConninfo() {
  if (const char* conninfo = std::getenv("LINELOC_BENCH_DB")) {
    return conninfo;
  }
  static const std::string conninfo = [] {
    // The owner role's: it migrates, and builds the baseline's index.
    const std::string cluster =
        lineloc::test::clusterConninfo("55432", lineloc::test::DatabaseRole::kOwner);
    Connection server(cluster);
    createDatabaseIfMissing(server, "lineloc_bench");
    // libpq takes the last value of a repeated keyword.
    return cluster + " dbname=lineloc_bench";
  }();
  return conninfo;
}

const lineloc::citymodel::SyntheticCityOptions& cityOptions() {
  static const lineloc::citymodel::SyntheticCityOptions options{.building_count = kCityBuildings};
  return options;
}

// The benchmark city, loaded once (lineloc-load --site synthetic
// --synthetic-buildings 100000 stores the same source), with the n-D index a
// plain ST_3DDWithin query needs.
// The model the queries run on, when not the synthetic city.
const char* cityModel() {
  return std::getenv("LINELOC_BENCH_CITY_MODEL");
}

const std::string& siteName() {
  static const std::string name = cityModel() == nullptr ? "synthetic"
                                  : std::getenv("LINELOC_BENCH_SITE")
                                      ? std::getenv("LINELOC_BENCH_SITE")
                                      : "city";
  return name;
}

Connection& cityDatabase() {
  static Connection connection = [] {
    Connection db(benchConninfo());
    if (db.exec("SELECT pg_is_in_recovery()").text(0, 0) == "t") {
      fmt::print("bench_db: querying a replica, which follows its primary's city and index\n");
      return db;
    }
    lineloc::db::applyMigrations(db, lineloc::db::embeddedMigrations());
    const std::string name = fmt::format("synthetic-{}-1", kCityBuildings);
    if (cityModel() != nullptr) {
      lineloc::db::LoadOptions options;
      options.site = siteName();
      lineloc::db::loadFile(cityModel(), options, &db, nullptr);
    } else if (db.execParams("SELECT 1 FROM source_file WHERE name = $1", {name}).rows() == 0) {
      lineloc::db::LoadOptions options;
      options.site = "synthetic";
      lineloc::db::storeModel(db, options, {name, name, ""},
                              lineloc::db::prepareSynthetic(cityOptions(), options), nullptr);
    }
    db.exec(
        "CREATE INDEX IF NOT EXISTS bench_line_geom_nd ON line USING gist (geom "
        "gist_geometry_ops_nd)");
    db.exec("ANALYZE");
    return db;
  }();
  return connection;
}

// The load benchmarks' database, beside the city's (created when missing).
Connection& loadDatabase() {
  static Connection connection = [] {
    Connection city(benchConninfo());
    const std::string name = city.exec("SELECT current_database()").text(0, 0) + "_load";
    createDatabaseIfMissing(city, name);
    // libpq takes the last value of a repeated keyword.
    Connection db(benchConninfo() + " dbname=" + name);
    lineloc::db::applyMigrations(db, lineloc::db::embeddedMigrations());
    return db;
  }();
  return connection;
}

std::vector<Eigen::Vector3d> queryCentres(Connection& db, const lineloc::db::Site& site) {
  std::vector<Eigen::Vector3d> centres;
  if (cityModel() != nullptr) {
    const lineloc::db::Result extent = db.execParams(
        "SELECT ST_XMin(e), ST_YMin(e), ST_ZMin(e), ST_XMax(e), ST_YMax(e) FROM "
        "(SELECT ST_3DExtent(geom) AS e FROM line WHERE site_id = $1) AS lines",
        {std::to_string(site.id)});
    const auto value = [&](int column) { return std::stod(extent.text(0, column)); };
    std::mt19937 random(1);
    std::uniform_real_distribution<double> x(value(0), value(3));
    std::uniform_real_distribution<double> y(value(1), value(4));
    for (int draw = 0; draw < kQueries; ++draw) {
      centres.push_back(Eigen::Vector3d(x(random), y(random), value(2) + 1.5) - site.origin);
    }
    return centres;
  }
  for (uint32_t draw = 0; draw < kQueries; ++draw) {
    const Eigen::Vector2d street = lineloc::citymodel::randomStreetPoint(cityOptions(), draw);
    centres.emplace_back(street.x() - site.origin.x(), street.y() - site.origin.y(), 1.5);
  }
  return centres;
}

// Median and p99 latency of each query benchmark, and the rates of each load
// benchmark, for the summary at the end.
std::map<std::string, std::pair<double, double>>& summary() {
  static std::map<std::string, std::pair<double, double>> values;
  return values;
}

void reportLatencies(benchmark::State& state, const std::string& name,
                     std::vector<double> latencies_ms, size_t lines) {
  std::sort(latencies_ms.begin(), latencies_ms.end());
  const double median_ms = latencies_ms[latencies_ms.size() / 2];
  const double p99_ms = latencies_ms[latencies_ms.size() * 99 / 100];
  summary()[name] = {median_ms, p99_ms};
  state.counters["median_ms"] = median_ms;
  state.counters["p99_ms"] = p99_ms;
  state.counters["lines_per_query"] = static_cast<double>(lines) / latencies_ms.size();
}

template <typename Query>
void timeQueries(benchmark::State& state, const std::string& name, Query&& query) {
  Connection& db = cityDatabase();
  const lineloc::db::Site site = *lineloc::db::findSite(db, siteName());
  const std::vector<Eigen::Vector3d> centres = queryCentres(db, site);
  std::vector<double> latencies_ms;
  size_t lines = 0;
  size_t next = 0;
  for (auto _ : state) {
    const auto start = std::chrono::steady_clock::now();
    const size_t found = query(db, site, centres[next++ % centres.size()]);
    latencies_ms.push_back(
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
            .count());
    lines += found;
  }
  reportLatencies(state, name, latencies_ms, lines);
}

void BM_LinesWithin150m_Lineloc(benchmark::State& state) {
  std::unique_ptr<lineloc::db::ModelLineQuery> prepared;
  timeQueries(state, "lineloc",
              [&](Connection& db, const lineloc::db::Site& site, const Eigen::Vector3d& centre) {
                if (!prepared)
                  prepared = std::make_unique<lineloc::db::ModelLineQuery>(db, site);
                const auto lines = prepared->linesWithin(centre, kRadius_m);
                benchmark::DoNotOptimize(lines.data());
                return lines.size();
              });
}

// What a user would write: one ST_3DDWithin filter, coordinates as text.
void BM_LinesWithin150m_PlainST3DDWithin(benchmark::State& state) {
  timeQueries(
      state, "plain",
      [](Connection& db, const lineloc::db::Site& site, const Eigen::Vector3d& centre) {
        const Eigen::Vector3d p = centre + site.origin;
        const lineloc::db::Result result = db.execParams(
            "SELECT id, building_id, kind, ST_X(ST_StartPoint(geom)), ST_Y(ST_StartPoint(geom)), "
            "ST_Z(ST_StartPoint(geom)), ST_X(ST_EndPoint(geom)), ST_Y(ST_EndPoint(geom)), "
            "ST_Z(ST_EndPoint(geom)) FROM line WHERE site_id = $1 AND "
            "ST_3DDWithin(geom, ST_SetSRID(ST_MakePoint($2, $3, $4), $5), $6)",
            {std::to_string(site.id), fmt::format("{:.17g}", p.x()), fmt::format("{:.17g}", p.y()),
             fmt::format("{:.17g}", p.z()), std::to_string(site.srid),
             fmt::format("{}", kRadius_m)});
        std::vector<lineloc::db::ModelLine> lines(result.rows());
        for (int row = 0; row < result.rows(); ++row) {
          const auto value = [&](int column) { return std::stod(result.text(row, column)); };
          lines[row].id = std::stoll(result.text(row, 0));
          lines[row].building_id = std::stoll(result.text(row, 1));
          lines[row].kind = static_cast<lineloc::db::LineKind>(std::stoi(result.text(row, 2)));
          lines[row].start_world = Eigen::Vector3d(value(3), value(4), value(5)) - site.origin;
          lines[row].end_world = Eigen::Vector3d(value(6), value(7), value(8)) - site.origin;
        }
        benchmark::DoNotOptimize(lines.data());
        return lines.size();
      });
}

// CPU seconds used so far by this process and by the server backend of `db`
// (from /proc; zero for the backend when the server runs elsewhere).
double cpuSeconds(Connection& db) {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  double seconds = usage.ru_utime.tv_sec + usage.ru_stime.tv_sec +
                   1e-6 * (usage.ru_utime.tv_usec + usage.ru_stime.tv_usec);
  const std::string pid = db.exec("SELECT pg_backend_pid()").text(0, 0);
  std::ifstream stat("/proc/" + pid + "/stat");
  std::string field;
  // Fields 14 and 15 (after the parenthesised command name) are utime and stime in ticks.
  for (int i = 1; i <= 15 && stat >> field; ++i) {
    if (i >= 14) {
      seconds += std::stod(field) / static_cast<double>(sysconf(_SC_CLK_TCK));
    }
  }
  return seconds;
}

// Times `load(round)`, which stores `buildings` buildings, and reports
// buildings per wall-clock second and per CPU second (client and server).
template <typename Load>
void timeLoads(benchmark::State& state, const std::string& name, int buildings, Load&& load) {
  Connection& db = loadDatabase();
  int round = 0;
  const double cpu_start_s = cpuSeconds(db);
  const auto wall_start = std::chrono::steady_clock::now();
  for (auto _ : state) {
    load(db, ++round);
  }
  const double wall_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  const double cpu_s = cpuSeconds(db) - cpu_start_s;
  const double loaded = static_cast<double>(state.iterations()) * buildings;
  state.counters["buildings_per_s"] = loaded / wall_s;
  state.counters["buildings_per_cpu_s"] = loaded / cpu_s;
  summary()[name] = {loaded / wall_s, loaded / cpu_s};
}

lineloc::db::PreparedModel gabledCity(int buildings, int round) {
  const lineloc::citymodel::SyntheticCityOptions city{
      .building_count = buildings, .seed = static_cast<uint32_t>(round), .gabled_fraction = 1.0};
  return lineloc::db::prepareSynthetic(city, {});
}

// Whole pipeline for 2,000 gabled LoD2 buildings, replacing the previous
// version of one of two sources each round.
void BM_LoadLod2Buildings_Lineloc(benchmark::State& state) {
  lineloc::db::LoadOptions options;
  options.site = "bench_load";
  timeLoads(state, "load lineloc", kLoadBuildings, [&](Connection& db, int round) {
    const std::string name = fmt::format("load-{}", round % 2);
    lineloc::db::storeModel(db, options, {name, std::to_string(round), ""},
                            gabledCity(kLoadBuildings, round), nullptr);
  });
}

std::string wktPoint(const Eigen::Vector3d& p) {
  return fmt::format("{:.17g} {:.17g} {:.17g}", p.x(), p.y(), p.z());
}

std::string wktPolygon(const lineloc::citymodel::Face& face) {
  std::string wkt = "POLYGON Z (";
  for (const auto& ring : face.rings) {
    wkt += wkt.back() == '(' ? "(" : ", (";
    for (const Eigen::Vector3d& point : ring) {
      wkt += wktPoint(point) + ", ";
    }
    wkt += wktPoint(ring.front()) + ")";
  }
  return wkt + ")";
}

// What a user would write: the same rows as lineloc-load, one INSERT each
// with WKT geometry, in one transaction; the line packs are derived once at
// the end (not by the trigger after every line, which would cost it more).
void storeRowByRow(Connection& db, const lineloc::db::Site& site, const std::string& source,
                   const lineloc::db::PreparedModel& prepared) {
  const std::string site_id = std::to_string(site.id);
  const std::string srid = std::to_string(site.srid);
  lineloc::db::inTransaction(db, [&] {
    db.exec("SELECT set_config('lineloc.line_packs_written', 'on', true)");
    db.execParams("DELETE FROM building WHERE site_id = $1 AND source = $2", {site_id, source});
    for (size_t i = 0; i < prepared.model.buildings.size(); ++i) {
      const lineloc::citymodel::Building& building = prepared.model.buildings[i];
      const std::string id =
          db.execParams(
                "INSERT INTO building (site_id, source, source_id, lod) VALUES ($1, $2, "
                "$3, $4) RETURNING id",
                {site_id, source, building.id, building.lod})
              .text(0, 0);
      for (size_t ordinal = 0; ordinal < building.faces.size(); ++ordinal) {
        const lineloc::citymodel::Face& face = building.faces[ordinal];
        const Eigen::Vector3d normal = lineloc::citymodel::faceNormal(face);
        db.execParams(
            "INSERT INTO face (site_id, building_id, ordinal, kind, normal_x, normal_y, "
            "normal_z, geom) VALUES ($1, $2, $3, $4, $5, $6, $7, ST_GeomFromText($8, $9))",
            {site_id, id, std::to_string(ordinal), std::to_string(static_cast<int>(face.kind)),
             fmt::format("{:.17g}", normal.x()), fmt::format("{:.17g}", normal.y()),
             fmt::format("{:.17g}", normal.z()), wktPolygon(face), srid});
      }
      for (const lineloc::citymodel::ExtractedLine& line : prepared.lines[i]) {
        db.execParams(
            "INSERT INTO line (site_id, building_id, kind, face_a, face_b, geom) VALUES ($1, $2, "
            "$3, $4, NULLIF($5, -1), ST_GeomFromText($6, $7))",
            {site_id, id, std::to_string(static_cast<int>(line.kind)), std::to_string(line.face_a),
             std::to_string(line.face_b),
             "LINESTRING Z (" + wktPoint(line.start) + ", " + wktPoint(line.end) + ")", srid});
      }
    }
    db.execParams(
        "SELECT refresh_line_packs(ARRAY(SELECT id FROM building WHERE site_id = $1 AND "
        "source = $2))",
        {site_id, source});
  });
}

void BM_LoadLod2Buildings_NaivePerRowInsert(benchmark::State& state) {
  timeLoads(state, "load naive", kNaiveLoadBuildings, [](Connection& db, int round) {
    const lineloc::db::Site site =
        lineloc::db::ensureSite(db, "bench_naive", 7415, Eigen::Vector3d(85000, 447000, 0));
    storeRowByRow(db, site, fmt::format("naive-{}", round % 2),
                  gabledCity(kNaiveLoadBuildings, round));
  });
}

BENCHMARK(BM_LinesWithin150m_Lineloc)->Iterations(kQueries)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_LinesWithin150m_PlainST3DDWithin)->Iterations(kQueries)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_LoadLod2Buildings_Lineloc)
    ->Iterations(6)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK(BM_LoadLod2Buildings_NaivePerRowInsert)
    ->Iterations(3)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

void printSummary() {
  const auto& values = summary();
  const auto has = [&](const char* name) { return values.count(name) > 0; };
  if (has("lineloc") && has("plain")) {
    const auto& [median_ms, p99_ms] = values.at("lineloc");
    const auto& [plain_median_ms, plain_p99_ms] = values.at("plain");
    fmt::print(
        "150 m query, site {}: lineloc median {:.3f} ms p99 {:.3f} ms; plain ST_3DDWithin "
        "median {:.3f} ms p99 {:.3f} ms; speed-up (median) {:.2f}x\n",
        siteName(), median_ms, p99_ms, plain_median_ms, plain_p99_ms, plain_median_ms / median_ms);
  }
  if (has("load lineloc") && has("load naive")) {
    const auto& [wall, cpu] = values.at("load lineloc");
    const auto& [naive_wall, naive_cpu] = values.at("load naive");
    fmt::print(
        "LoD2 load: lineloc {:.0f} buildings/s ({:.0f} per CPU second); per-row INSERT {:.0f} "
        "buildings/s ({:.0f} per CPU second); speed-up {:.1f}x (wall), {:.1f}x (CPU)\n",
        wall, cpu, naive_wall, naive_cpu, wall / naive_wall, cpu / naive_cpu);
  }
}

}  // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  try {
    // The database every benchmark needs, reached before any of them runs.
    Connection(benchConninfo()).exec("SELECT 1");
    benchmark::RunSpecifiedBenchmarks();
  } catch (const std::exception& error) {
    fmt::print(stderr,
               "bench_db: {}\nbench_db: needs a PostGIS server: deploy/pg.sh start, or "
               "LINELOC_BENCH_DB naming an existing database\n",
               error.what());
    benchmark::Shutdown();
    return 1;
  }
  benchmark::Shutdown();
  printSummary();
  return 0;
}
