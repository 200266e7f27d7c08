// The rate-limited log: the first lines of each interval logged, the rest
// counted into one summary once their interval has ended, no event lost or
// counted twice.
#include <gtest/gtest.h>
#include <spdlog/sinks/ostream_sink.h>

#include <algorithm>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "common/logging/rate_limited_log.h"

namespace lineloc {
namespace {

constexpr int64_t kSecondNs = 1'000'000'000;

class RateLimitedLogTest : public ::testing::Test {
 protected:
  RateLimitedLogTest() {
    logger_ = std::make_shared<spdlog::logger>(
        "rate_limited_log_test", std::make_shared<spdlog::sinks::ostream_sink_st>(output_));
    logger_->set_pattern("%v");
  }

  std::vector<std::string> lines() const {
    std::vector<std::string> result;
    std::istringstream stream(output_.str());
    for (std::string line; std::getline(stream, line);) {
      result.push_back(line);
    }
    return result;
  }

  // The events the summaries among `lines` count.
  static uint64_t summarised(const std::vector<std::string>& lines) {
    // "dropped LineSets: N more not logged in the last S s"
    const std::string prefix = "dropped LineSets: ";
    const std::string middle = " more not logged in the last ";
    uint64_t total = 0;
    for (const std::string& line : lines) {
      const size_t count_end = line.find(middle);
      if (line.rfind(prefix, 0) == 0 && count_end != std::string::npos && line.back() == 's') {
        total += std::stoull(line.substr(prefix.size(), count_end - prefix.size()));
      }
    }
    return total;
  }

  std::ostringstream output_;
  std::shared_ptr<spdlog::logger> logger_;
};

TEST_F(RateLimitedLogTest, LogsTheFirstLinesOfAnIntervalAndSummarisesTheRestAfterIt) {
  RateLimitedLog log("dropped LineSets", 3, 1.0, spdlog::level::warn, logger_);
  for (int i = 0; i < 10; ++i) {
    log.log(i * 1000, "dropped LineSet #" + std::to_string(i));
  }
  EXPECT_EQ(lines(), (std::vector<std::string>{"dropped LineSet #0", "dropped LineSet #1",
                                               "dropped LineSet #2"}));
  log.flush(kSecondNs / 2);
  EXPECT_EQ(lines().size(), 3u) << "no summary before the interval ends";
  log.log(kSecondNs + 5, "dropped LineSet #10");
  const std::vector<std::string> after = lines();
  ASSERT_EQ(after.size(), 5u);
  EXPECT_EQ(after[3], "dropped LineSets: 7 more not logged in the last 1.0 s");
  EXPECT_EQ(after[4], "dropped LineSet #10");
  EXPECT_EQ(log.logged(), 4u);
  EXPECT_EQ(log.suppressed(), 7u);
}

TEST_F(RateLimitedLogTest, FlushSummarisesAnEndedIntervalOnceWithoutANewEvent) {
  RateLimitedLog log("dropped LineSets", 1, 0.5, spdlog::level::warn, logger_);
  log.log(0, "first");
  log.log(1, "second");
  log.log(2, "third");
  log.flush(kSecondNs);
  log.flush(2 * kSecondNs);
  EXPECT_EQ(lines(), (std::vector<std::string>{
                         "first", "dropped LineSets: 2 more not logged in the last 1.0 s"}));
}

TEST_F(RateLimitedLogTest, EveryEventIsLoggedOrSummarisedExactlyOnce) {
  RateLimitedLog log("dropped LineSets", 5, 0.1, spdlog::level::warn, logger_);
  constexpr int kEvents = 5000;
  // 5,000 drops in 2.5 s.
  for (int i = 0; i < kEvents; ++i) {
    log.log(i * 500'000LL, "dropped LineSet");
  }
  log.flush(10 * kSecondNs);
  const std::vector<std::string> logged = lines();
  const uint64_t plain = std::count(logged.begin(), logged.end(), "dropped LineSet");
  EXPECT_EQ(plain, log.logged());
  EXPECT_EQ(summarised(logged), log.suppressed());
  EXPECT_EQ(log.logged() + log.suppressed(), static_cast<uint64_t>(kEvents));
  // 25 intervals: at most 5 lines and one summary each.
  EXPECT_LE(logged.size(), 26u * 6u);
}

TEST_F(RateLimitedLogTest, LogsItsLinesAndSummariesAtItsLevel) {
  logger_->set_pattern("%l %v");
  RateLimitedLog log("map failures", 1, 1.0, spdlog::level::err, logger_);
  log.log(0, "map failed");
  log.log(1, "map failed again");
  log.flush(kSecondNs);
  EXPECT_EQ(lines(),
            (std::vector<std::string>{"error map failed",
                                      "error map failures: 1 more not logged in the last 1.0 s"}));
}

TEST(RateLimitedLog, RefusesAnEmptyBudget) {
  EXPECT_THROW(RateLimitedLog("x", 0, 1.0), std::invalid_argument);
  EXPECT_THROW(RateLimitedLog("x", 1, 0.0), std::invalid_argument);
}

}  // namespace
}  // namespace lineloc
