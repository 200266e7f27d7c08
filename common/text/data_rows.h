// Text files of data rows, one record per line: the whole file read at once,
// and its rows visited with their line numbers (1-based), blank lines and
// '#' comments skipped, so that a parser's errors can name file and line.
#pragma once

#include <functional>
#include <string>
#include <string_view>

namespace lineloc {

// The file's bytes; throws std::runtime_error "cannot read <what> from
// <path>" when it cannot be opened.
std::string readTextFile(const std::string& path, const std::string& what);

void forEachDataRow(std::string_view text,
                    const std::function<void(const std::string& row, int line_number)>& visit);

}  // namespace lineloc
