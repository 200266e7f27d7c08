// YAML from outside: a document parses, and syntax errors and nesting 70,000
// levels deep (flow and block style) are errors naming the source.
#include <gtest/gtest.h>

#include <sstream>
#include <stdexcept>
#include <string>

#include "common/config/yaml_document.h"

namespace lineloc {
namespace {

YAML::Node load(const std::string& text) {
  std::istringstream stream(text);
  return loadYamlDocument(stream, "config.yml");
}

std::string errorOf(const std::string& text) {
  try {
    load(text);
  } catch (const std::runtime_error& error) {
    return error.what();
  }
  ADD_FAILURE() << "accepted: " << text.substr(0, 80);
  return "";
}

TEST(YamlDocument, ParsesADocument) {
  const YAML::Node root = load("rate_hz: 30\npose: [1, 2, 3]\n");
  EXPECT_EQ(root["rate_hz"].as<int>(), 30);
  EXPECT_EQ(root["pose"].size(), 3u);
}

TEST(YamlDocument, SyntaxErrorsNameTheSource) {
  EXPECT_NE(errorOf("a: [1, 2\n").find("config.yml: not valid YAML: "), std::string::npos);
}

TEST(YamlDocument, NestingTooDeepIsSaidSoWithThePlace) {
  const std::string flow = "a: " + std::string(70000, '[') + std::string(70000, ']') + "\n";
  EXPECT_NE(errorOf(flow).find("config.yml: not valid YAML: nested too deeply (line 1, column"),
            std::string::npos)
      << errorOf(flow);
  std::string block;
  for (int level = 0; level < 3000; ++level) {
    block += std::string(level, ' ') + "k:\n";
  }
  EXPECT_NE(errorOf(block).find("config.yml: not valid YAML: nested too deeply"), std::string::npos)
      << errorOf(block);
}

}  // namespace
}  // namespace lineloc
