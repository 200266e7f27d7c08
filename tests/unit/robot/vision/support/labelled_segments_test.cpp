#include "labelled_segments.h"

#include <gtest/gtest.h>

#include <sstream>

namespace lineloc::testing {
namespace {

LabelledSegments read(const std::string& text) {
  std::istringstream in(text);
  return readLabelledSegments(in, "labels.txt");
}

// The message of the std::invalid_argument that reading `text` throws.
std::string errorOf(const std::string& text) {
  try {
    read(text);
  } catch (const std::invalid_argument& error) {
    return error.what();
  }
  return "no error";
}

TEST(LabelledSegments, ReadsCommentsBlankLinesAndSegments) {
  const LabelledSegments labels = read(
      "# comment\n"
      "\n"
      "   # indented comment\n"
      "region 10 0 110 50.5\n"
      "  12 3 40.25 3\n"
      "20 40 20 10\n");
  EXPECT_EQ(labels.region.min(), Eigen::Vector2d(10.0, 0.0));
  EXPECT_EQ(labels.region.max(), Eigen::Vector2d(110.0, 50.5));
  ASSERT_EQ(labels.segments.size(), 2u);
  EXPECT_EQ(labels.segments[0].start, Eigen::Vector2d(12.0, 3.0));
  EXPECT_EQ(labels.segments[0].end, Eigen::Vector2d(40.25, 3.0));
  EXPECT_EQ(labels.segments[1].end, Eigen::Vector2d(20.0, 10.0));
}

TEST(LabelledSegments, MalformedLinesNameTheFileAndLine) {
  const std::string region = "region 0 0 100 100\n";
  EXPECT_EQ(errorOf(region + "1 2 3\n").rfind("labels.txt:2: expected a segment", 0), 0u);
  EXPECT_EQ(errorOf(region + "1 2 3 4 5\n").rfind("labels.txt:2: expected a segment", 0), 0u);
  EXPECT_EQ(errorOf(region + "1 2 x 4\n").rfind("labels.txt:2: expected a segment", 0), 0u);
  EXPECT_EQ(errorOf(region + "1 2 nan 4\n").rfind("labels.txt:2: expected a segment", 0), 0u);
  EXPECT_EQ(errorOf(region + "1 2 inf 4\n").rfind("labels.txt:2: expected a segment", 0), 0u);
  EXPECT_EQ(errorOf(region + "5 5 5 5\n"), "labels.txt:2: a segment of zero length");
  EXPECT_EQ(errorOf(region + region), "labels.txt:2: a second region");
  EXPECT_EQ(errorOf("region 0 0 100\n").rfind("labels.txt:1: region needs", 0), 0u);
  EXPECT_EQ(errorOf("region 0 0 0 100\n").rfind("labels.txt:1: region needs", 0), 0u);
  EXPECT_EQ(errorOf("region 0 0 100 100 7\n").rfind("labels.txt:1: region needs", 0), 0u);
  EXPECT_EQ(errorOf("1 2 3 4\n"), "labels.txt: no region line");
  EXPECT_EQ(errorOf(""), "labels.txt: no region line");
}

TEST(LabelledSegments, AMissingFileIsAnError) {
  EXPECT_THROW(readLabelledSegments(std::string("no/such/folder/labels.txt")),
               std::invalid_argument);
}

}  // namespace
}  // namespace lineloc::testing
