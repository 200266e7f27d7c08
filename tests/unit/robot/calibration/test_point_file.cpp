#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

#include "robot/calibration/point_file.h"

namespace lineloc {
namespace {

void expectError(const std::string& text, const std::string& expected_part) {
  try {
    parsePointPairs(text, "view.txt");
    FAIL() << "no error for '" << text << "'";
  } catch (const std::runtime_error& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find("view.txt"), std::string::npos) << message;
    EXPECT_NE(message.find(expected_part), std::string::npos) << message;
  }
}

TEST(PointFile, ReadsAnyNumberOfPairsPerLine) {
  const std::vector<Eigen::Vector2d> points =
      parsePointPairs("1 2 3 4\n5\t6\r\n\n  7 +8e1 # comment 9 9\n-0.5\n1.25\n", "view.txt");
  ASSERT_EQ(points.size(), 5u);
  EXPECT_EQ(points[0], Eigen::Vector2d(1, 2));
  EXPECT_EQ(points[1], Eigen::Vector2d(3, 4));
  EXPECT_EQ(points[2], Eigen::Vector2d(5, 6));
  EXPECT_EQ(points[3], Eigen::Vector2d(7, 80));
  EXPECT_EQ(points[4], Eigen::Vector2d(-0.5, 1.25));
}

TEST(PointFile, MalformedInputIsNamedWithItsLine) {
  expectError("1 2\n3 x4\n", "view.txt:2: 'x4' is not a number");
  expectError("1 2 3\n", "odd number of coordinates (3)");
  expectError("", "no coordinates");
  expectError("# only a comment\n", "no coordinates");
  expectError("1 nan\n", "view.txt:1: non-finite value 'nan'");
  expectError("\n\ninf 2\n", "view.txt:3: non-finite value");
  expectError("1e999 2\n", "is not a number");
  expectError("1,2 3,4\n", "'1,2' is not a number");
  expectError("+\n", "'+' is not a number");
}

TEST(PointFile, UnreadableFileIsNamed) {
  try {
    readPointFile("/nonexistent/model.txt");
    FAIL();
  } catch (const std::runtime_error& error) {
    EXPECT_NE(std::string(error.what()).find("/nonexistent/model.txt"), std::string::npos);
  }
}

}  // namespace
}  // namespace lineloc
