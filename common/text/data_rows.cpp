#include "common/text/data_rows.h"

#include <fmt/format.h>

#include <fstream>
#include <sstream>
#include <stdexcept>

namespace lineloc {

std::string readTextFile(const std::string& path, const std::string& what) {
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    throw std::runtime_error(fmt::format("cannot read {} from {}", what, path));
  }
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

void forEachDataRow(std::string_view text,
                    const std::function<void(const std::string& row, int line_number)>& visit) {
  std::istringstream in{std::string(text)};
  std::string row;
  for (int number = 1; std::getline(in, row); ++number) {
    if (!row.empty() && row.front() != '#') {
      visit(row, number);
    }
  }
}

}  // namespace lineloc
