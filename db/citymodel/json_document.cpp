#include "db/citymodel/json_document.h"

#include <fmt/format.h>

#include "db/citymodel/city_model.h"

namespace lineloc::citymodel {

std::optional<size_t> findJsonNestingBeyond(std::string_view text, int max_depth) {
  int depth = 0;
  bool in_string = false;
  bool escaped = false;
  for (size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (in_string) {
      if (escaped) {
        escaped = false;
      } else if (c == '\\') {
        escaped = true;
      } else if (c == '"') {
        in_string = false;
      }
      continue;
    }
    if (c == '"') {
      in_string = true;
    } else if (c == '[' || c == '{') {
      if (++depth > max_depth) {
        return i;
      }
    } else if ((c == ']' || c == '}') && depth > 0) {
      --depth;
    }
  }
  return std::nullopt;
}

nlohmann::json parseJsonDocument(std::string_view text, const std::string& source,
                                 const std::string& where, int max_depth) {
  if (const std::optional<size_t> offset = findJsonNestingBeyond(text, max_depth)) {
    throw ModelError(source, "", "JSON nested too deeply",
                     fmt::format("{}arrays and objects nest deeper than {} levels at byte {}",
                                 where, max_depth, *offset));
  }
  try {
    return nlohmann::json::parse(text);
  } catch (const nlohmann::json::exception& error) {
    throw ModelError(source, "", "malformed JSON", where + error.what());
  }
}

}  // namespace lineloc::citymodel
