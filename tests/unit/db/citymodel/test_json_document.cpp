// The nesting bound of the city-model JSON parser: depth counted as the parser
// would, brackets in strings left out, a 70,000-deep document refused with the
// file, the limit and the place named.
#include <gtest/gtest.h>

#include "db/citymodel/city_model.h"
#include "db/citymodel/json_document.h"

namespace lineloc::citymodel {
namespace {

std::string nestedArrays(int depth) {
  return std::string(depth, '[') + std::string(depth, ']');
}

TEST(JsonNesting, CountsArraysAndObjectsAsTheParserNestsThem) {
  EXPECT_FALSE(findJsonNestingBeyond("1", 0));
  EXPECT_EQ(findJsonNestingBeyond("[]", 0), 0u);
  EXPECT_FALSE(findJsonNestingBeyond(R"({"a":[1,{"b":[]}]})", 4));
  EXPECT_EQ(findJsonNestingBeyond(R"({"a":[1,{"b":[]}]})", 3), 13u);
  // Siblings do not add up: each closes before the next opens.
  EXPECT_FALSE(findJsonNestingBeyond("[[],[],[[]],[]]", 3));
}

TEST(JsonNesting, BracketsInStringsDoNotCount) {
  EXPECT_FALSE(findJsonNestingBeyond(R"(["[[[{{{", "]]]"])", 1));
  EXPECT_FALSE(findJsonNestingBeyond(R"(["\"[[[", "\\"])", 1));
  // A closing bracket in a string cannot hide the depth of what follows it.
  EXPECT_EQ(findJsonNestingBeyond(R"([ "]", [ "]", [ "]", []]]])", 3), 21u);
}

TEST(JsonNesting, ADepthBombIsRefusedBeforeParsingNamingFileAndLimit) {
  const std::string bomb = R"({"attributes":)" + nestedArrays(70000) + "}";
  try {
    parseJsonDocument(bomb, "bomb.json", "", 256);
    FAIL() << "expected a ModelError";
  } catch (const ModelError& error) {
    EXPECT_EQ(error.reason(), "JSON nested too deeply");
    const std::string message = error.what();
    EXPECT_NE(message.find("bomb.json"), std::string::npos) << message;
    EXPECT_NE(message.find("256 levels"), std::string::npos) << message;
    EXPECT_NE(message.find("byte 269"), std::string::npos) << message;
  }
}

TEST(JsonNesting, NestingUpToTheLimitParses) {
  EXPECT_EQ(parseJsonDocument(nestedArrays(256), "deep.json", "", 256).size(), 1u);
  EXPECT_THROW(parseJsonDocument(nestedArrays(257), "deep.json", "", 256), ModelError);
}

TEST(JsonNesting, SyntaxErrorsStayMalformedJson) {
  try {
    parseJsonDocument("[1,", "cut.json", "line 3: ", 256);
    FAIL() << "expected a ModelError";
  } catch (const ModelError& error) {
    EXPECT_EQ(error.reason(), "malformed JSON");
    EXPECT_NE(std::string(error.what()).find("line 3: "), std::string::npos) << error.what();
  }
}

}  // namespace
}  // namespace lineloc::citymodel
