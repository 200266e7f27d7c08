// Benchmarks of the building database (paper §3.1: lines near the robot,
// fast), on a PostGIS server named by LINELOC_BENCH_DB (a libpq connection
// string; default the deploy/pg.sh cluster, database lineloc_bench, which is
// created and filled with a 100,000-building synthetic city on first run):
//  - load throughput, LoD2 buildings per second through the whole pipeline
//    (generate, validate, extract lines, COPY, commit);
//  - the 150 m query around random street positions: ModelLineQuery (index
//    box, binary EWKB, exact distance in C++) beside a plain ST_3DDWithin
//    query decoded from text, each query's latency recorded so the median and
//    99th percentile are reported, and their ratio.
#include <benchmark/benchmark.h>
#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <map>

#include "db/loader/loader.h"
#include "db/migrations.h"
#include "db/model_line_query.h"
#include "db/site.h"

namespace {

using lineloc::db::Connection;

constexpr int kCityBuildings = 100000;
constexpr double kRadius_m = 150.0;
constexpr int kQueries = 400;

std::string benchConninfo() {
  const char* conninfo = std::getenv("LINELOC_BENCH_DB");
  return conninfo != nullptr ? conninfo
                             : "host=127.0.0.1 port=55432 user=lineloc dbname=lineloc_bench";
}

const lineloc::citymodel::SyntheticCityOptions& cityOptions() {
  static const lineloc::citymodel::SyntheticCityOptions options{.building_count = kCityBuildings};
  return options;
}

// The benchmark city, loaded once (lineloc-load --site synthetic
// --synthetic-buildings 100000 stores the same source).
Connection& cityDatabase() {
  static Connection connection = [] {
    Connection db(benchConninfo());
    lineloc::db::applyMigrations(db, lineloc::db::embeddedMigrations());
    const std::string name = fmt::format("synthetic-{}-1", kCityBuildings);
    if (db.execParams("SELECT 1 FROM source_file WHERE name = $1", {name}).rows() == 0) {
      lineloc::db::LoadOptions options;
      options.site = "synthetic";
      lineloc::db::storeModel(db, options, {name, name, ""},
                              lineloc::db::prepareSynthetic(cityOptions(), options), nullptr);
      db.exec("ANALYZE");
    }
    return db;
  }();
  return connection;
}

std::vector<Eigen::Vector3d> queryCentres(const lineloc::db::Site& site) {
  std::vector<Eigen::Vector3d> centres;
  for (uint32_t draw = 0; draw < kQueries; ++draw) {
    const Eigen::Vector2d street = lineloc::citymodel::randomStreetPoint(cityOptions(), draw);
    centres.emplace_back(street.x() - site.origin.x(), street.y() - site.origin.y(), 1.5);
  }
  return centres;
}

// Median and p99 latency of each query benchmark, for the summary at the end.
std::map<std::string, std::pair<double, double>>& latencySummary() {
  static std::map<std::string, std::pair<double, double>> summary;
  return summary;
}

void reportLatencies(benchmark::State& state, const std::string& name,
                     std::vector<double> latencies_ms, size_t lines) {
  std::sort(latencies_ms.begin(), latencies_ms.end());
  const double median_ms = latencies_ms[latencies_ms.size() / 2];
  const double p99_ms = latencies_ms[latencies_ms.size() * 99 / 100];
  latencySummary()[name] = {median_ms, p99_ms};
  state.counters["median_ms"] = median_ms;
  state.counters["p99_ms"] = p99_ms;
  state.counters["lines_per_query"] = static_cast<double>(lines) / latencies_ms.size();
}

template <typename Query>
void timeQueries(benchmark::State& state, const std::string& name, Query&& query) {
  Connection& db = cityDatabase();
  const lineloc::db::Site site = *lineloc::db::findSite(db, "synthetic");
  const std::vector<Eigen::Vector3d> centres = queryCentres(site);
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

// Whole pipeline for 2,000 gabled LoD2 buildings into a scratch site, one core.
void BM_LoadLod2Buildings(benchmark::State& state) {
  Connection& db = cityDatabase();
  lineloc::db::LoadOptions options;
  options.site = "bench_load";
  int round = 0;
  for (auto _ : state) {
    lineloc::citymodel::SyntheticCityOptions city{
        .building_count = 2000, .seed = static_cast<uint32_t>(++round), .gabled_fraction = 1.0};
    const std::string name = fmt::format("load-{}", round % 2);
    lineloc::db::storeModel(db, options, {name, std::to_string(round), ""},
                            lineloc::db::prepareSynthetic(city, options), nullptr);
  }
  state.SetItemsProcessed(state.iterations() * 2000);
  state.counters["buildings_per_s"] = benchmark::Counter(
      static_cast<double>(state.iterations() * 2000), benchmark::Counter::kIsRate);
}

BENCHMARK(BM_LinesWithin150m_Lineloc)->Iterations(kQueries)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_LinesWithin150m_PlainST3DDWithin)->Iterations(kQueries)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_LoadLod2Buildings)
    ->Iterations(3)
    ->Repetitions(3)
    ->ReportAggregatesOnly(true)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

}  // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  const auto& summary = latencySummary();
  const auto lineloc = summary.find("lineloc");
  const auto plain = summary.find("plain");
  if (lineloc != summary.end() && plain != summary.end()) {
    fmt::print(
        "150 m query, {} buildings: lineloc median {:.3f} ms p99 {:.3f} ms; plain ST_3DDWithin "
        "median {:.3f} ms p99 {:.3f} ms; speed-up (median) {:.2f}x\n",
        kCityBuildings, lineloc->second.first, lineloc->second.second, plain->second.first,
        plain->second.second, plain->second.first / lineloc->second.first);
  }
  return 0;
}
