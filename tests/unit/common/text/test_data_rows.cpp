#include <gtest/gtest.h>

#include <vector>

#include "common/text/data_rows.h"

namespace lineloc {
namespace {

TEST(DataRows, CommentsAndBlankLinesAreSkippedAndRowsKeepTheirLineNumbers) {
  std::vector<std::pair<std::string, int>> rows;
  forEachDataRow("# header\n1 2\n\n3 4\n# more\n5 6",
                 [&](const std::string& row, int number) { rows.emplace_back(row, number); });
  ASSERT_EQ(rows.size(), 3u);
  EXPECT_EQ(rows[0], std::make_pair(std::string("1 2"), 2));
  EXPECT_EQ(rows[1], std::make_pair(std::string("3 4"), 4));
  EXPECT_EQ(rows[2], std::make_pair(std::string("5 6"), 6));
}

TEST(DataRows, AFileThatCannotBeReadIsNamed) {
  try {
    readTextFile("/nonexistent/edges.txt", "façade edges");
    FAIL() << "read a file that does not exist";
  } catch (const std::runtime_error& error) {
    EXPECT_STREQ(error.what(), "cannot read façade edges from /nonexistent/edges.txt");
  }
}

}  // namespace
}  // namespace lineloc
