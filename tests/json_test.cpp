// The JSON reader and escaper of host/common (json.hpp): values keep their
// line and column, refusals are JsonError with the whole message and where
// the offending token starts, and quote() escapes for the reports. The scene
// loader's messages built on it are in scene_test.cpp (SceneErrors.*).
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "json.hpp"

namespace json = mc1::json;

namespace {

// The JsonError that parsing `text` throws; fails the test if none is thrown.
json::JsonError error_of(const std::string& text, const std::vector<json::ItemLimit>& limits = {}) {
  try {
    json::parse(text, "r.json", limits);
  } catch (const json::JsonError& e) {
    return e;
  }
  ADD_FAILURE() << "accepted: " << text;
  return json::JsonError("", 0, 0);
}

TEST(Json, ValuesKeepTheirPlaceAndNegativeZero) {
  json::Value v = json::parse("{\"a\": [1,\n  -0, \"s\"], \"b\": {}}", "t");
  const json::Value& a = *v.find("a");
  EXPECT_EQ(a.items[1].line, 2);
  EXPECT_EQ(a.items[1].column, 3);
  EXPECT_TRUE(std::signbit(a.items[1].number));  // "-0" stays -0 (its FP24 sign bit)
  EXPECT_EQ(a.items[2].string, "s");
  EXPECT_EQ(v.find("b")->column, 18);
  EXPECT_EQ(v.find("c"), nullptr);
}

TEST(Json, QuoteEscapesForJsonReports) {
  EXPECT_EQ(json::quote("a\"b\\c\n\x01"), "\"a\\\"b\\\\c\\n\\u0001\"");
  EXPECT_EQ(json::quote("\xff"), "\"\xEF\xBF\xBD\"");  // not UTF-8: U+FFFD
}

TEST(Json, SyntaxErrorCarriesLineAndColumn) {
  const json::JsonError e = error_of("{\"ops\": [\n  {\"op\": \"add\",, \"vectors\": 1}]}");
  EXPECT_STREQ(e.what(), "r.json:2:16: JSON syntax: expected a key string");
  EXPECT_EQ(e.line, 2);
  EXPECT_EQ(e.column, 16);  // the second comma
  const json::JsonError dup = error_of("{\"a\": 1,\n \"a\": 2}");
  EXPECT_STREQ(dup.what(), "r.json:2:2: JSON syntax: duplicate key \"a\"");
  EXPECT_EQ(dup.line, 2);
  EXPECT_EQ(dup.column, 2);
  const json::JsonError end = error_of("[1,\n");
  EXPECT_STREQ(end.what(), "r.json:2:1: JSON syntax: unexpected end of input");
  EXPECT_EQ(end.line, 2);
}

TEST(Json, ItemLimitRefusesTheElementBeyondIt) {
  const std::vector<json::ItemLimit> limits = {{{"list", "[]", "x"}, 2, "more than 2 x in all"}};
  EXPECT_NO_THROW(json::parse("{\"list\": [{\"x\": [1]}, {\"x\": [2]}]}", "r.json", limits));
  // Counted over every element of "list" together: the third x is refused.
  const json::JsonError e = error_of("{\"list\": [{\"x\": [1]},\n  {\"x\": [2,\n    3]}]}", limits);
  EXPECT_STREQ(e.what(), "r.json:3: list[1].x[1]: more than 2 x in all");
  EXPECT_EQ(e.line, 3);
  EXPECT_EQ(e.column, 5);
}

TEST(Json, IsAStdRuntimeError) {  // callers that know only std::exception still see the message
  try {
    json::parse("nul", "r.json");
    FAIL() << "accepted";
  } catch (const std::runtime_error& e) {
    EXPECT_STREQ(e.what(), "r.json:1:1: JSON syntax: invalid literal 'nul' (expected true, false or null)");
  }
}

}  // namespace
