// Parsing of a city model's JSON text (RFC 8259) with its nesting bounded
// before the parse: arrays and objects nested deeper than the bound are refused
// by a scan of the text, so no recursive handling of the parsed value (copies,
// serialisation, the readers' walks) can run out of stack on hostile input.
#pragma once

#include <cstddef>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>

namespace lineloc::citymodel {

// The byte offset in `text` of the first array or object that opens deeper than
// `max_depth` (the outermost value is depth 1), or nullopt when there is none.
// Brackets inside strings do not count. Exact for every prefix that is valid
// JSON, so it agrees with the parser wherever the parser gets to.
std::optional<size_t> findJsonNestingBeyond(std::string_view text, int max_depth);

// Parses `text`. Throws ModelError naming `source` ("JSON nested too deeply",
// with the byte offset and the limit) when it nests deeper than `max_depth`,
// and ModelError ("malformed JSON") on a syntax error; `where` prefixes the
// detail ("line 3: ").
nlohmann::json parseJsonDocument(std::string_view text, const std::string& source,
                                 const std::string& where, int max_depth);

}  // namespace lineloc::citymodel
