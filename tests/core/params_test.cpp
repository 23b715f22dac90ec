// ParamBinder: every kind of field set from text, enums through their name table, ranges
// checked once with one message naming `--set algo.MODULE.FIELD`, shortest defaults.
#include "core/params.hpp"

#include <gtest/gtest.h>

#include "core/error.hpp"

namespace slambox {
namespace {

enum class Shape { kRound, kSquare };
const EnumNames<Shape> kShapeNames = {{Shape::kRound, "round"}, {Shape::kSquare, "square"}};

struct Config {
  double sigma_m = 0.2;
  int count = 3;
  bool flag = false;
  Shape shape = Shape::kSquare;
};

ParamBinder Bound(Config& c) {
  ParamBinder b;
  b.Bind("sigma_m", c.sigma_m, "m", "noise", Above(0));
  b.Bind("count", c.count, "-", "how many", Between(1, 10));
  b.Bind("flag", c.flag, "-", "a switch");
  b.Bind("shape", c.shape, kShapeNames, "the shape");
  return b;
}

std::string ErrorOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(ParamBinder, ListsDefaultsShortestAndEnumNames) {
  Config c;
  const ParamBinder b = Bound(c);
  const auto& l = b.List();
  ASSERT_EQ(l.size(), 4u);
  EXPECT_EQ(l[0].default_value, "0.2");  // not 0.20000000000000001
  EXPECT_EQ(l[1].default_value, "3");
  EXPECT_EQ(l[3].type, "enum");
  EXPECT_EQ(l[3].default_value, "square");
  EXPECT_EQ(l[3].unit, "round|square");
  EXPECT_STREQ(NameOf(kShapeNames, Shape::kRound), "round");
}

TEST(ParamBinder, AppliesEveryKindAndValidatesRanges) {
  Config c;
  const ParamBinder b = Bound(c);
  b.Apply({{"sigma_m", "0.05"}, {"count", "10"}, {"flag", "true"}, {"shape", "round"}}, "m");
  EXPECT_EQ(c.sigma_m, 0.05);
  EXPECT_EQ(c.count, 10);
  EXPECT_TRUE(c.flag);
  EXPECT_EQ(c.shape, Shape::kRound);
  EXPECT_NO_THROW(b.Validate("m"));
  b.Apply({{"count", "11"}}, "m");
  const std::string msg = ErrorOf([&] { b.Validate("my-slam"); });
  EXPECT_NE(msg.find("--set algo.my-slam.count"), std::string::npos) << msg;
  EXPECT_NE(msg.find("count = 11 is out of range"), std::string::npos) << msg;
  EXPECT_NE(msg.find(">= 1 and <= 10"), std::string::npos) << msg;
  c.count = 1;
  c.sigma_m = 0.0;  // Above(0) is open
  EXPECT_NE(ErrorOf([&] { b.Validate("m"); }).find("> 0"), std::string::npos);
}

TEST(ParamBinder, BadTextNamesTheFieldAndTheChoices) {
  Config c;
  const ParamBinder b = Bound(c);
  const std::string shape = ErrorOf([&] { b.Apply({{"shape", "oval"}}, "m"); });
  EXPECT_NE(shape.find("--set algo.m.shape"), std::string::npos) << shape;
  EXPECT_NE(shape.find("round|square"), std::string::npos) << shape;
  EXPECT_EQ(c.shape, Shape::kSquare);  // unchanged
  EXPECT_NE(ErrorOf([&] { b.Apply({{"sigma_m", "nan"}}, "m"); }).find("a finite number"), std::string::npos);
  EXPECT_NE(ErrorOf([&] { b.Apply({{"count", "2.5"}}, "m"); }).find("an integer"), std::string::npos);
  EXPECT_NE(ErrorOf([&] { b.Apply({{"flag", "yes"}}, "m"); }).find("true or false"), std::string::npos);
  const std::string unknown = ErrorOf([&] { b.Apply({{"sigma", "1"}}, "m"); });
  EXPECT_NE(unknown.find("sigma_m, count, flag, shape"), std::string::npos) << unknown;
}

TEST(Range, ContainsAndDescribes) {
  EXPECT_TRUE(InRange(AtLeast(0), 0.0));
  EXPECT_FALSE(InRange(Above(0), 0.0));
  EXPECT_TRUE(InRange(Between(-1, 1), 1.0));
  EXPECT_FALSE(InRange(Range{.min = 0, .max = 1, .max_open = true}, 1.0));
  EXPECT_EQ(Describe(Between(0, 16)), ">= 0 and <= 16");
  EXPECT_EQ(Describe(Above(0)), "> 0");
  EXPECT_EQ(Describe(Range{}), "");
}

}  // namespace
}  // namespace slambox
