#include <gtest/gtest.h>

#include <sstream>
#include <string>
#include <vector>

#include "common/progress/progress_meter.h"

namespace lineloc {
namespace {

std::vector<std::string> linesOf(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) {
    lines.push_back(line);
  }
  return lines;
}

TEST(ProgressMeter, ALogGetsALineEveryPeriodWithTheRateAndTheTimeLeft) {
  double now_s = 0.0;
  std::ostringstream out;
  ProgressMeter meter("loading city.json", "buildings", out, ProgressMeter::Style::kLog, 10.0,
                      [&] { return now_s; });
  // Four buildings a second: at 10 s, 40 of 100 done, 60 left take 15 s.
  for (int second = 1; second <= 25; ++second) {
    now_s = second;
    meter.update(4 * second, 100);
  }
  const std::vector<std::string> lines = linesOf(out.str());
  ASSERT_EQ(lines.size(), 3u);
  EXPECT_EQ(lines[0], "loading city.json: 40/100 buildings (40 %), 4/s, 15 s left");
  EXPECT_EQ(lines[1], "loading city.json: 80/100 buildings (80 %), 4/s, 5 s left");
  EXPECT_EQ(lines[2], "loading city.json: 100/100 buildings (100 %), 4/s in 25 s");
}

TEST(ProgressMeter, FinishedWorkIsReportedOnce) {
  double now_s = 0.0;
  std::ostringstream out;
  ProgressMeter meter("rendering", "frames", out, ProgressMeter::Style::kLog, 10.0,
                      [&] { return now_s; });
  now_s = 90.0;
  meter.update(300, 300);
  now_s = 200.0;
  meter.update(300, 300);
  EXPECT_EQ(out.str(), "rendering: 300/300 frames (100 %), 3.3/s in 1 min 30 s\n");
}

TEST(ProgressMeter, ATerminalLineIsRedrawnInPlaceAtMostTenTimesASecond) {
  double now_s = 0.0;
  std::ostringstream out;
  ProgressMeter meter("rendering", "frames", out, ProgressMeter::Style::kTerminal, 10.0,
                      [&] { return now_s; });
  now_s = 0.05;
  meter.update(1, 4);  // too soon after the start
  now_s = 0.5;
  meter.update(2, 4);
  now_s = 0.55;
  meter.update(3, 4);  // too soon after the last
  now_s = 1.0;
  meter.update(4, 4);
  const std::string text = out.str();
  EXPECT_EQ(text,
            "\rrendering [###############...............] 2/4 frames  4/s, 1 s left\033[K"
            "\rrendering [##############################] 4/4 frames  4/s in 1 s\033[K\n");
}

TEST(ProgressMeter, LongWaitsAreInMinutesAndHours) {
  double now_s = 0.0;
  std::ostringstream out;
  ProgressMeter meter("seeds", "drives", out, ProgressMeter::Style::kLog, 10.0,
                      [&] { return now_s; });
  now_s = 70.0;
  meter.update(1, 100);  // 70 s a drive, 99 left: 6930 s
  EXPECT_EQ(out.str(), "seeds: 1/100 drives (1 %), 0.014/s, 1 h 55 min left\n");
}

}  // namespace
}  // namespace lineloc
