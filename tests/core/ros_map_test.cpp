#include "core/ros_map.hpp"

#include <gtest/gtest.h>
#include <png.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>

#include "core/error.hpp"
#include "core/map_image.hpp"

namespace slambox {
namespace {

namespace fs = std::filesystem;

class RosMapTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("slambox_ros_map_" + std::to_string(::getpid()) + "_" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string Write(const std::string& name, const std::string& content) {
    std::ofstream(dir_ / name, std::ios::binary) << content;
    return (dir_ / name).string();
  }
  // A 3 x 2 P5 image: top row black, white, mid grey; bottom row 205, 254, 0.
  std::string SmallPgm() { return Write("m.pgm", std::string("P5\n3 2\n255\n") + std::string("\x00\xff\x80\xcd\xfe\x00", 6)); }
  std::string Yaml(const std::string& body) { return Write("m.yaml", body); }
  static std::string Keys(const std::string& except, const std::string& extra = "") {
    std::string out;
    const std::pair<const char*, const char*> keys[] = {{"image", "image: m.pgm\n"},
                                                        {"resolution", "resolution: 0.1\n"},
                                                        {"origin", "origin: [-1.5, 2.0, 0.0]\n"},
                                                        {"negate", "negate: 0\n"},
                                                        {"occupied_thresh", "occupied_thresh: 0.65\n"},
                                                        {"free_thresh", "free_thresh: 0.196\n"}};
    for (const auto& [k, line] : keys)
      if (except != k) out += line;
    return out + extra;
  }
  std::string ErrorOf(const std::string& yaml) {
    try {
      ReadRosMap(yaml);
    } catch (const InputError& e) {
      return e.what();
    }
    return "";
  }
  fs::path dir_;
};

OccupancyGrid RandomTrinaryGrid(int w, int h, unsigned seed) {
  std::mt19937 rng(seed);
  OccupancyGrid g;
  g.width = w;
  g.height = h;
  g.resolution_m = 0.05 + 0.01 * (seed % 7) + 1e-13;  // not a short decimal: needs %.17g
  g.origin_m = {-3.1415926535897931 * seed, 2.718281828459045};
  for (int i = 0; i < w * h; ++i) g.cells.push_back(std::array<std::int8_t, 3>{-1, 0, 100}[rng() % 3]);
  return g;
}

TEST_F(RosMapTest, TrinaryGridRoundTripsBitExactly) {
  for (unsigned seed = 1; seed <= 5; ++seed) {
    const OccupancyGrid g = RandomTrinaryGrid(17 + int(seed), 9 + 3 * int(seed), seed);
    const std::string yaml = (dir_ / "out" / "algo.yaml").string();
    WriteRosMap(yaml, g);
    EXPECT_TRUE(fs::exists(dir_ / "out" / "algo.pgm"));
    const OccupancyGrid r = ReadRosMap(yaml);
    EXPECT_EQ(r.width, g.width);
    EXPECT_EQ(r.height, g.height);
    EXPECT_EQ(r.resolution_m, g.resolution_m);
    EXPECT_EQ(r.origin_m, g.origin_m);
    EXPECT_EQ(r.cells, g.cells);
  }
}

TEST_F(RosMapTest, WrittenYamlHasEveryNav2KeyAndTheImageIsTopRowFirst) {
  OccupancyGrid g;
  g.width = 2;
  g.height = 2;
  g.resolution_m = 0.25;
  g.origin_m = {1, -2};
  g.cells = {100, -1, 0, 10};  // bottom row (iy = 0): occupied, unknown; top row: free, 10 (free)
  WriteRosMap((dir_ / "g.yaml").string(), g);
  std::stringstream yaml;
  yaml << std::ifstream(dir_ / "g.yaml").rdbuf();
  for (const char* key : {"image: g.pgm\n", "mode: trinary\n", "resolution: 0.25\n", "origin: [1, -2, 0]\n", "negate: 0\n",
                          "occupied_thresh: 0.65000000000000002\n", "free_thresh: 0.19600000000000001\n"})
    EXPECT_NE(yaml.str().find(key), std::string::npos) << key << " in\n" << yaml.str();
  std::stringstream pgm;
  pgm << std::ifstream(dir_ / "g.pgm", std::ios::binary).rdbuf();
  EXPECT_EQ(pgm.str(), std::string("P5\n2 2\n255\n\xfe\xfe\x00\xcd", 15));
}

TEST_F(RosMapTest, IntermediateValuesQuantizeAsNav2MapSaver) {
  OccupancyGrid g;
  g.width = 6;
  g.height = 1;
  g.cells = {20, 21, 64, 65, 101, -7};  // <= rint(19.6) = 20 free; >= 65 occupied; else unknown
  WriteRosMap((dir_ / "q.yaml").string(), g);
  EXPECT_EQ(ReadRosMap((dir_ / "q.yaml").string()).cells, (std::vector<std::int8_t>{0, -1, -1, 100, -1, -1}));
}

TEST_F(RosMapTest, ReadsEveryFieldAndFlipsRows) {
  SmallPgm();
  const OccupancyGrid g = ReadRosMap(Yaml(Keys("", "mode: trinary\nextra_tool_key: 3\n")));
  EXPECT_EQ(g.width, 3);
  EXPECT_EQ(g.height, 2);
  EXPECT_EQ(g.resolution_m, 0.1);
  EXPECT_EQ(g.origin_m, Eigen::Vector2d(-1.5, 2.0));
  // Grid row 0 is the image's bottom row (205 unknown, 254 free, 0 occupied); 0x80 -> occ 0.498: unknown.
  EXPECT_EQ(g.cells, (std::vector<std::int8_t>{-1, 0, 100, 100, 0, -1}));
}

TEST_F(RosMapTest, NegateSwapsBlackAndWhite) {
  SmallPgm();
  const OccupancyGrid g = ReadRosMap(Yaml(Keys("negate", "negate: 1\n")));
  // occ = shade: 205 -> 0.80 occupied, 254 -> occupied, 0 -> free; 0x80 -> 0.502 unknown.
  EXPECT_EQ(g.cells, (std::vector<std::int8_t>{100, 100, 0, 0, 100, -1}));
  EXPECT_EQ(ReadRosMap(Yaml(Keys("negate", "negate: true\n"))).cells, g.cells);  // nav2 also takes a bool
}

TEST_F(RosMapTest, ScaleAndRawModes) {
  Write("m.pgm", std::string("P2\n# text PGM with a comment\n4 1\n100\n0 100 50 60\n"));
  // scale: occ = 1 - shade; 0 -> occupied, 1 -> free, 0.5 -> (0.5-0.196)/(0.65-0.196)*100 = 67, 0.4 -> 45.
  EXPECT_EQ(ReadRosMap(Yaml(Keys("", "mode: scale\n"))).cells, (std::vector<std::int8_t>{100, 0, 67, 45}));
  // raw: value = round(shade * 255): 0, 255 (-> unknown), 128 (-> unknown), 153 (-> unknown)
  Write("m.pgm", std::string("P5\n3 1\n255\n\x00\x64\x65", 14));
  EXPECT_EQ(ReadRosMap(Yaml(Keys("", "mode: raw\n"))).cells, (std::vector<std::int8_t>{0, 100, -1}));
}

TEST_F(RosMapTest, SixteenBitPgm) {
  Write("m.pgm", std::string("P5 2 1 65535\n\xff\xff\x00\x01", 17));
  EXPECT_EQ(ReadRosMap(Yaml(Keys(""))).cells, (std::vector<std::int8_t>{0, 100}));
}

TEST_F(RosMapTest, PngWithAlphaAveragesAlphaInTrinaryMode) {
  // 2 x 1 RGBA: opaque white (free); white with alpha 0 -> shade (3*1 + 0)/4 = 0.75, occ 0.25: unknown.
  png_image png{};
  png.version = PNG_IMAGE_VERSION;
  png.width = 2;
  png.height = 1;
  png.format = PNG_FORMAT_RGBA;
  const png_byte px[8] = {255, 255, 255, 255, 255, 255, 255, 0};
  ASSERT_TRUE(png_image_write_to_file(&png, (dir_ / "m.png").c_str(), 0, px, 0, nullptr));
  EXPECT_EQ(ReadRosMap(Yaml(Keys("image", "image: m.png\n"))).cells, (std::vector<std::int8_t>{0, -1}));
  // scale mode: any transparency is unknown.
  EXPECT_EQ(ReadRosMap(Yaml(Keys("image", "image: m.png\nmode: scale\n"))).cells, (std::vector<std::int8_t>{0, -1}));
}

TEST_F(RosMapTest, AbsoluteImagePath) {
  SmallPgm();
  EXPECT_EQ(ReadRosMap(Yaml(Keys("image", "image: " + (dir_ / "m.pgm").string() + "\n"))).width, 3);
}

TEST_F(RosMapTest, EveryMissingKeyIsNamed) {
  SmallPgm();
  for (const char* key : {"image", "resolution", "origin", "negate", "occupied_thresh", "free_thresh"}) {
    const std::string e = ErrorOf(Yaml(Keys(key)));
    EXPECT_NE(e.find(std::string("missing key '") + key + "'"), std::string::npos) << e;
    EXPECT_NE(e.find("m.yaml"), std::string::npos) << e;
    EXPECT_NE(e.find("fix:"), std::string::npos) << e;
  }
}

TEST_F(RosMapTest, BadValuesNameTheLineAndTheFix) {
  SmallPgm();
  struct Case {
    std::string except, line, message;
  };
  const Case cases[] = {
      {"free_thresh", "free_thresh: 0.7\n", "0 <= free_thresh < occupied_thresh <= 1"},
      {"occupied_thresh", "occupied_thresh: 1.5\n", "0 <= free_thresh < occupied_thresh <= 1"},
      {"free_thresh", "free_thresh: -0.1\n", "0 <= free_thresh < occupied_thresh <= 1"},
      {"free_thresh", "free_thresh: abc\n", "'free_thresh' must be a finite number"},
      {"negate", "negate: 2\n", "'negate' must be 0 or 1"},
      {"resolution", "resolution: 0\n", "'resolution' must be positive"},
      {"resolution", "resolution: .nan\n", "'resolution' must be a finite number"},
      {"origin", "origin: [1, 2]\n", "'origin' must have 3 elements"},
      {"origin", "origin: [1, 2, 0.5]\n", "origin yaw != 0"},
      {"image", "image: ''\n", "'image' must name a file"},
      {"image", "image: none.pgm\n", "cannot open the map image"},
      {"", "mode: fancy\n", "unknown mode 'fancy'"},
  };
  for (const auto& c : cases) {
    const std::string e = ErrorOf(Yaml(Keys(c.except, c.line)));
    EXPECT_NE(e.find(c.message), std::string::npos) << c.line << " -> " << e;
    EXPECT_NE(e.find("m.yaml:"), std::string::npos) << "line number missing: " << e;
  }
  EXPECT_NE(ErrorOf(Yaml("image: [unclosed\n")).find("malformed YAML"), std::string::npos);
  EXPECT_NE(ErrorOf((dir_ / "absent.yaml").string()).find("cannot open the map file"), std::string::npos);
}

TEST_F(RosMapTest, MalformedImagesAreErrorsNamingBothFiles) {
  const std::pair<std::string, std::string> cases[] = {
      {std::string("P5\n3 2\n255\n\x00\xff", 13), "truncated PGM"},
      {"P5\n3\n", "malformed PGM header"},
      {"P5\n3 2\n0\n", "maxval 0 outside 1..65535"},
      {"P5\n0 2\n255\n", "no pixels"},
      {"P2\n2 1\n255\n7\n", "truncated or malformed P2"},
      {"P2\n2 1\n10\n7 11\n", "above maxval"},
      {"GIF89a", "not a PGM (P5/P2) or PNG image"},
      {std::string("\x89PNG\r\n\x1a\nxxxx", 12), "malformed PNG"},
      {"P5\n99999 99999 255\n", "exceeds the limit"},
  };
  for (const auto& [bytes, message] : cases) {
    Write("m.pgm", bytes);
    const std::string e = ErrorOf(Yaml(Keys("")));
    EXPECT_NE(e.find(message), std::string::npos) << message << " -> " << e;
    EXPECT_NE(e.find("m.yaml"), std::string::npos) << e;
    EXPECT_NE(e.find("m.pgm"), std::string::npos) << e;
  }
}

}  // namespace
}  // namespace slambox
