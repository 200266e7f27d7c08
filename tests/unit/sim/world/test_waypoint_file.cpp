#include <gtest/gtest.h>

#include "sim/world/waypoint_file.h"

namespace lineloc {
namespace {

TEST(WaypointFile, ParsesSpacesTabsCommasAndComments) {
  const auto points = parseWaypoints("# x y\n1 2\n\n3.5,\t-4e1\r\n  # turn\n-7 8", "route.txt");
  ASSERT_EQ(points.size(), 3u);
  EXPECT_EQ(points[1], Eigen::Vector2d(3.5, -40.0));
  EXPECT_EQ(points[2], Eigen::Vector2d(-7.0, 8.0));
}

TEST(WaypointFile, MalformedLinesNameTheSourceAndLine) {
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"1 2\n3\n", "route.txt:2: expected two numbers"},
      {"1 2\n3 4 5\n", "route.txt:2: expected two numbers"},
      {"1 2\nx y\n", "route.txt:2: expected two numbers"},
      {"1 2\n3 4x\n", "route.txt:2: expected two numbers"},
      {"1 2\nnan 4\n", "route.txt:2: non-finite"},
      {"1 2\n1 2\n", "route.txt:2: repeats"},
      {"# only a comment\n5 6\n", "route.txt: a route needs at least two waypoints"},
      {"", "route.txt: a route needs at least two waypoints"},
  };
  for (const auto& [text, message] : cases) {
    try {
      parseWaypoints(text, "route.txt");
      ADD_FAILURE() << "accepted: " << text;
    } catch (const std::runtime_error& error) {
      EXPECT_NE(std::string(error.what()).find(message), std::string::npos)
          << error.what() << " | expected: " << message;
    }
  }
}

TEST(WaypointFile, MissingFileIsNamed) {
  try {
    readWaypointFile("no_such_route.txt");
    FAIL();
  } catch (const std::runtime_error& error) {
    EXPECT_NE(std::string(error.what()).find("no_such_route.txt"), std::string::npos);
  }
}

}  // namespace
}  // namespace lineloc
