#include "db/citymodel/obj_reader.h"

#include <fmt/format.h>

#include <charconv>
#include <set>

#include "db/citymodel/polygon_geometry.h"

namespace lineloc::citymodel {
namespace {

struct Statement {
  std::string_view keyword;
  std::vector<std::string_view> arguments;
};

Statement split(std::string_view line) {
  Statement statement;
  size_t begin = 0;
  while (begin < line.size()) {
    begin = line.find_first_not_of(" \t\r", begin);
    if (begin == std::string_view::npos) {
      break;
    }
    const size_t end = std::min(line.find_first_of(" \t\r", begin), line.size());
    const std::string_view token = line.substr(begin, end - begin);
    if (statement.keyword.empty()) {
      statement.keyword = token;
    } else {
      statement.arguments.push_back(token);
    }
    begin = end;
  }
  return statement;
}

double parseNumber(std::string_view token) {
  double value = 0.0;
  const auto [end, error] = std::from_chars(token.data(), token.data() + token.size(), value);
  if (error != std::errc() || end != token.data() + token.size() || !std::isfinite(value)) {
    throw std::invalid_argument(fmt::format("'{}' is not a finite number", token));
  }
  return value;
}

// The 0-based vertex of an `f` argument "i", "i/t", "i//n" or "i/t/n".
size_t parseVertexIndex(std::string_view token, size_t vertex_count) {
  const std::string_view index_text = token.substr(0, token.find('/'));
  long long index = 0;
  const auto [end, error] =
      std::from_chars(index_text.data(), index_text.data() + index_text.size(), index);
  if (error != std::errc() || end != index_text.data() + index_text.size() || index == 0) {
    throw std::invalid_argument(fmt::format("'{}' is not a vertex index", token));
  }
  const long long resolved = index > 0 ? index - 1 : static_cast<long long>(vertex_count) + index;
  if (resolved < 0 || resolved >= static_cast<long long>(vertex_count)) {
    throw std::out_of_range(
        fmt::format("index {} with {} vertices defined so far", index, vertex_count));
  }
  return static_cast<size_t>(resolved);
}

class ObjParser {
 public:
  ObjParser(const std::string& source, const Eigen::Vector3d& offset, const ReadOptions& options,
            bool objects_by_o)
      : source_(source), offset_(offset), options_(options), objects_by_o_(objects_by_o) {}

  void line(std::string_view text, int line_number) {
    const Statement statement = split(text.substr(0, text.find('#')));
    const std::string where = fmt::format("line {}", line_number);
    try {
      if (statement.keyword == "v") {
        vertex(statement);
      } else if (statement.keyword == "f") {
        face(statement);
      } else if (statement.keyword == (objects_by_o_ ? "o" : "g")) {
        startObject(statement, line_number);
      }
    } catch (const std::out_of_range& error) {
      invalid("vertex index out of range", where + ": " + error.what());
    } catch (const std::invalid_argument& error) {
      invalid("malformed OBJ", where + ": " + error.what());
    }
  }

  CityModel finish() {
    closeObject();
    return std::move(model_);
  }

 private:
  void vertex(const Statement& statement) {
    if (statement.arguments.size() < 3) {
      throw std::invalid_argument("a vertex needs x y z");
    }
    const Eigen::Vector3d file_point(parseNumber(statement.arguments[0]),
                                     parseNumber(statement.arguments[1]),
                                     parseNumber(statement.arguments[2]));
    vertices_.push_back(zUpPoint(file_point, options_.up_axis) + offset_);
  }

  void face(const Statement& statement) {
    if (statement.arguments.size() < 3) {
      throw std::invalid_argument("a face needs at least 3 vertices");
    }
    Face face;
    face.rings.emplace_back();
    for (std::string_view argument : statement.arguments) {
      face.rings.front().push_back(vertices_[parseVertexIndex(argument, vertices_.size())]);
    }
    face.kind = surfaceKindFromNormal(faceNormal(face));
    current_.faces.push_back(std::move(face));
  }

  void startObject(const Statement& statement, int line_number) {
    closeObject();
    current_.id = statement.arguments.empty() ? fmt::format("object-at-line-{}", line_number)
                                              : std::string(statement.arguments.front());
    object_invalid_ = false;
  }

  void invalid(const std::string& reason, const std::string& detail) {
    const std::string id = current_.id.empty() ? "(unnamed)" : current_.id;
    handleInvalidObject(ModelError(source_, id, reason, detail), options_.invalid_objects,
                        model_.skipped);
    object_invalid_ = true;
  }

  void closeObject() {
    if (!object_invalid_ && !current_.faces.empty()) {
      if (current_.id.empty()) {
        current_.id = "(unnamed)";
      }
      if (!ids_.insert(current_.id).second) {
        current_.id = fmt::format("{}#{}", current_.id, model_.buildings.size());
      }
      current_.type = "Building";
      model_.buildings.push_back(std::move(current_));
    }
    current_ = Building{};
    object_invalid_ = false;
  }

  const std::string& source_;
  Eigen::Vector3d offset_;
  const ReadOptions& options_;
  bool objects_by_o_;
  std::vector<Eigen::Vector3d> vertices_;
  Building current_;
  bool object_invalid_ = false;
  std::set<std::string> ids_;
  CityModel model_;
};

bool hasObjectStatements(std::string_view text) {
  return text.rfind("o ", 0) == 0 || text.find("\no ") != std::string_view::npos;
}

}  // namespace

CityModel readWavefrontObj(std::string_view text, const std::string& source,
                           const Eigen::Vector3d& offset, const ReadOptions& options) {
  ObjParser parser(source, offset, options, hasObjectStatements(text));
  int line_number = 0;
  size_t begin = 0;
  while (begin < text.size()) {
    const size_t end = std::min(text.find('\n', begin), text.size());
    parser.line(text.substr(begin, end - begin), ++line_number);
    begin = end + 1;
  }
  return parser.finish();
}

}  // namespace lineloc::citymodel
