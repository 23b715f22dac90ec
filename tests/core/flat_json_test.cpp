// The flat JSON object parser of the exec protocol's answers: the JSON grammar (strict),
// numbers bit for bit as a general JSON parser reads them, escapes, and the bare
// NaN/Infinity tokens Python writes.
#include "core/flat_json.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>
#include <random>

namespace slambox {
namespace {

TEST(FlatJson, NumbersAgreeBitForBitWithAGeneralParser) {
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(-1.0, 1.0), e(-300.0, 300.0);
  FlatObject o;
  char buf[512];
  for (int i = 0; i < 20000; ++i) {
    const double v = u(rng) * std::pow(10.0, e(rng));
    for (const char* format : {"%.17g", "%.6e", "%.3f", "%.1E"}) {
      std::snprintf(buf, sizeof buf, format, v);
      const std::string line = std::string(R"({"v":)") + buf + "}";
      ASSERT_EQ(ParseFlatObject(line, o), "") << line;
      EXPECT_EQ(o.Find("v")->number, nlohmann::json::parse(line)["v"].get<double>()) << line;
    }
  }
}

TEST(FlatJson, ReadsEveryValueKindAndEscape) {
  FlatObject o;
  ASSERT_EQ(ParseFlatObject(R"( { "a" : -0 , "b":1E+2,"c":"x\"\\\/\n\u00e9\ud83d\ude00","d":true,"e":null,"f":[1, -2.5e-3 ],"g":[]} )", o), "");
  EXPECT_TRUE(o.Find("a")->integer);
  EXPECT_TRUE(std::signbit(o.Find("a")->number));
  EXPECT_EQ(o.Find("b")->number, 100.0);
  EXPECT_FALSE(o.Find("b")->integer);
  EXPECT_EQ(o.Find("c")->text, "x\"\\/\n\xC3\xA9\xF0\x9F\x98\x80");
  EXPECT_TRUE(o.Find("d")->boolean);
  EXPECT_EQ(o.Find("e")->kind, FlatValue::Kind::kNull);
  EXPECT_EQ(o.Find("f")->numbers, (std::vector<double>{1.0, -2.5e-3}));
  EXPECT_TRUE(o.Find("g")->numbers.empty());
  EXPECT_EQ(o.Find("zz"), nullptr);
  ASSERT_EQ(ParseFlatObject("{}", o), "");
  EXPECT_TRUE(o.members.empty());
}

TEST(FlatJson, FlagsPythonsNonFiniteTokens) {
  FlatObject o;
  ASSERT_EQ(ParseFlatObject(R"({"a":NaN,"b":-Infinity,"c":[1,Infinity],"d":"NaN"})", o), "");
  EXPECT_TRUE(std::isnan(o.Find("a")->number) && o.Find("a")->non_finite);
  EXPECT_EQ(o.Find("b")->number, -INFINITY);
  EXPECT_TRUE(o.Find("c")->non_finite);
  EXPECT_EQ(o.Find("c")->numbers[1], INFINITY);
  EXPECT_EQ(o.Find("d")->text, "NaN");
}

TEST(FlatJson, RejectsWhatIsNotOneFlatJsonObject) {
  FlatObject o;
  for (const char* bad : {"", "hello", "[1]", "{", "{\"a\":1", "{\"a\":1,}", "{\"a\" 1}", "{a:1}", "{\"a\":01}",
                          "{\"a\":1.}", "{\"a\":.5}", "{\"a\":+1}", "{\"a\":1e}", "{\"a\":-}", "{\"a\":1}x",
                          "{\"a\":1}{}", "{\"a\":{\"b\":1}}", "{\"a\":[\"s\"]}", "{\"a\":[1,]}", "{\"a\":1,\"a\":2}",
                          "{\"a\":\"\\x\"}", "{\"a\":\"\\ud800\"}", "{\"a\":\"tab\there\"}", "{\"a\":tru}",
                          "{\"a\":1e999}"}) {
    const std::string error = ParseFlatObject(bad, o);
    EXPECT_NE(error, "") << bad;
    EXPECT_NE(error.find("column"), std::string::npos) << bad << ": " << error;
  }
}

}  // namespace
}  // namespace slambox
