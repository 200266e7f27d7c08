// The backbone's stage statistics: median, 99th percentile and maximum of
// each stage over the recent answers, as printed and written to its stats file.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "backbone/service/backbone_service.h"

namespace lineloc {
namespace {

// 200 answers whose total took 1, 2, ..., 200 ms and whose map stage took 0.1 ms.
BackboneCounters twoHundredAnswers() {
  BackboneCounters counters;
  for (int64_t ms = 1; ms <= 200; ++ms) {
    StageTimingsNs timings;
    timings.map = 100'000;
    timings.total = ms * 1'000'000;
    counters.recent_timings.push_back(timings);
  }
  counters.answered = 200;
  counters.robots = 3;
  counters.robots_forgotten = 2;
  return counters;
}

TEST(StagePercentiles, GiveMedianNinetyNinthPercentileAndMaximumOfEachStage) {
  const std::vector<StagePercentiles> stages = stagePercentiles(twoHundredAnswers());
  ASSERT_EQ(stages.size(), 5u);
  EXPECT_EQ(stages.front().stage, "map");
  EXPECT_DOUBLE_EQ(stages.front().max_ms, 0.1);
  const StagePercentiles& total = stages.back();
  EXPECT_EQ(total.stage, "total");
  EXPECT_DOUBLE_EQ(total.median_ms, 100.0);
  EXPECT_DOUBLE_EQ(total.p99_ms, 198.0);
  EXPECT_DOUBLE_EQ(total.max_ms, 200.0);
}

TEST(StagePercentiles, AreZeroBeforeTheFirstAnswer) {
  for (const StagePercentiles& stage : stagePercentiles(BackboneCounters{})) {
    EXPECT_EQ(stage.max_ms, 0.0) << stage.stage;
  }
}

TEST(CountersJson, HoldsEachStagesMaximum) {
  const std::filesystem::path path =
      std::filesystem::path(::testing::TempDir()) / "backbone-stats-test.json";
  writeCountersJson(twoHundredAnswers(), path.string());
  const nlohmann::json json = nlohmann::json::parse(std::ifstream(path));
  EXPECT_EQ(json.at("answered"), 200);
  EXPECT_EQ(json.at("robots"), 3);
  EXPECT_EQ(json.at("robots_forgotten"), 2);
  EXPECT_DOUBLE_EQ(json.at("stage_ms").at("total").at("max").get<double>(), 200.0);
  EXPECT_DOUBLE_EQ(json.at("stage_ms").at("total").at("p99").get<double>(), 198.0);
  std::filesystem::remove(path);
}

}  // namespace
}  // namespace lineloc
