#include "core/ros_map.hpp"

#include <yaml-cpp/yaml.h>

#include <cassert>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>

#include "core/atomic_file.hpp"
#include "core/error.hpp"
#include "core/map_image.hpp"

namespace slambox {

namespace fs = std::filesystem;

namespace {

constexpr std::uint8_t kOccupiedPixel = 0, kFreePixel = 254, kUnknownPixel = 205;  // nav2 map_saver

int LineOf(const YAML::Node& node) { return node.Mark().is_null() ? 0 : node.Mark().line + 1; }

const YAML::Node Required(const std::string& path, const YAML::Node& doc, const char* key, const std::string& fix) {
  const YAML::Node node = doc[key];
  if (!node) throw InputError(path, 0, std::string("missing key '") + key + "'", fix);
  return node;
}

double Number(const std::string& path, const YAML::Node& node, const char* key) {
  try {
    const double v = node.as<double>();
    if (std::isfinite(v)) return v;
  } catch (const YAML::Exception&) {
  }
  throw InputError(path, LineOf(node), std::string("'") + key + "' must be a finite number", std::string("write e.g. ") + key + ": 0.05");
}

}  // namespace

void WriteRosMap(const std::string& yaml_path, const OccupancyGrid& grid, const RosMapWriteOptions& options) {
  assert(grid.width > 0 && grid.height > 0 && grid.cells.size() == std::size_t(grid.width) * grid.height);
  const int free_max = static_cast<int>(std::rint(options.free_thresh * 100.0));
  const int occupied_min = static_cast<int>(std::rint(options.occupied_thresh * 100.0));
  std::vector<std::uint8_t> pixels(grid.cells.size());
  for (int y = 0; y < grid.height; ++y)
    for (int x = 0; x < grid.width; ++x) {
      const int cell = grid.cells[std::size_t(grid.height - 1 - y) * grid.width + x];  // top row = max y
      std::uint8_t p = kUnknownPixel;
      if (cell >= 0 && cell <= 100) p = cell <= free_max ? kFreePixel : cell >= occupied_min ? kOccupiedPixel : kUnknownPixel;
      pixels[std::size_t(y) * grid.width + x] = p;
    }
  const fs::path yaml(yaml_path);
  const fs::path image = fs::path(yaml).replace_extension(".pgm");
  WritePgm(image.string(), grid.width, grid.height, pixels);
  char text[512];
  // %.17g: resolution and origin round-trip bit-exactly.
  std::snprintf(text, sizeof text,
                "image: %s\nmode: trinary\nresolution: %.17g\norigin: [%.17g, %.17g, 0]\nnegate: 0\n"
                "occupied_thresh: %.17g\nfree_thresh: %.17g\n",
                image.filename().c_str(), grid.resolution_m, grid.origin_m.x(), grid.origin_m.y(),
                options.occupied_thresh, options.free_thresh);
  WriteFileAtomic(yaml_path, std::string(text));
}

OccupancyGrid ReadRosMap(const std::string& path) {
  return ReadRosMap(path, [&](const std::string& file) {
    std::ifstream in(file, std::ios::binary);
    if (!in)
      throw InputError(file, 0, file == path ? "cannot open the map file" : "cannot open the map image",
                       file == path ? "check the path" : "check the `image:` key of the map YAML");
    return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  });
}

OccupancyGrid ReadRosMap(const std::string& path, const MapFileReader& read) {
  YAML::Node doc;
  try {
    doc = YAML::Load(read(path));
  } catch (const YAML::Exception& e) {
    throw InputError(path, e.mark.is_null() ? 0 : e.mark.line + 1, "malformed YAML: " + e.msg, "fix the syntax");
  }
  if (!doc.IsMap()) throw InputError(path, 0, "a map YAML is a mapping of keys", "write image:, resolution:, origin:, ...");
  const YAML::Node image_node = Required(path, doc, "image", "name the map image, e.g. image: map.pgm");
  std::string image;
  if (image_node.IsScalar()) image = image_node.as<std::string>();
  if (image.empty()) throw InputError(path, LineOf(image_node), "'image' must name a file", "write e.g. image: map.pgm");
  fs::path image_path(image);
  if (image_path.is_relative()) image_path = fs::path(path).parent_path() / image_path;

  OccupancyGrid grid;
  const YAML::Node res = Required(path, doc, "resolution", "give the cell size in metres, e.g. resolution: 0.05");
  grid.resolution_m = Number(path, res, "resolution");
  if (grid.resolution_m <= 0)
    throw InputError(path, LineOf(res), "'resolution' must be positive", "give the cell size in metres, e.g. resolution: 0.05");
  const YAML::Node origin = Required(path, doc, "origin", "give the lower-left pixel's pose, e.g. origin: [0, 0, 0]");
  if (!origin.IsSequence() || origin.size() != 3)
    throw InputError(path, LineOf(origin), "'origin' must have 3 elements [x, y, yaw]", "write e.g. origin: [-10, -10, 0]");
  const double ox = Number(path, origin[0], "origin"), oy = Number(path, origin[1], "origin");
  if (Number(path, origin[2], "origin") != 0.0)
    throw InputError(path, LineOf(origin), "a rotated map (origin yaw != 0) is not supported: slambox grids are axis-aligned",
                     "rotate the image instead and set the yaw to 0");
  grid.origin_m = {ox, oy};

  const YAML::Node neg = Required(path, doc, "negate", "write negate: 0 (black = occupied) or 1");
  bool negate = false;
  try {
    const int v = neg.as<int>();  // nav2 takes an int, then a bool
    if (v != 0 && v != 1) throw YAML::Exception(neg.Mark(), "");
    negate = v == 1;
  } catch (const YAML::Exception&) {
    try {
      negate = neg.as<bool>();
    } catch (const YAML::Exception&) {
      throw InputError(path, LineOf(neg), "'negate' must be 0 or 1", "write negate: 0 (black = occupied) or 1");
    }
  }
  const YAML::Node occ_node = Required(path, doc, "occupied_thresh", "write e.g. occupied_thresh: 0.65");
  const YAML::Node free_node = Required(path, doc, "free_thresh", "write e.g. free_thresh: 0.196");
  const double occupied_thresh = Number(path, occ_node, "occupied_thresh");
  const double free_thresh = Number(path, free_node, "free_thresh");
  if (free_thresh < 0 || occupied_thresh > 1 || free_thresh >= occupied_thresh)
    throw InputError(path, LineOf(occ_node), "thresholds must satisfy 0 <= free_thresh < occupied_thresh <= 1 (got free " +
                                                 std::to_string(free_thresh) + ", occupied " + std::to_string(occupied_thresh) + ")",
                     "use e.g. occupied_thresh: 0.65 and free_thresh: 0.196");
  RosMapMode mode = RosMapMode::kTrinary;
  if (const YAML::Node m = doc["mode"]) {
    const std::string s = m.IsScalar() ? m.as<std::string>() : "";
    if (s == "trinary") mode = RosMapMode::kTrinary;
    else if (s == "scale") mode = RosMapMode::kScale;
    else if (s == "raw") mode = RosMapMode::kRaw;
    else throw InputError(path, LineOf(m), "unknown mode '" + s + "'", "write mode: trinary, scale or raw");
  }

  MapImage img;
  try {
    img = DecodeMapImage(image_path.string(), read(image_path.string()));
  } catch (const InputError& e) {  // name the YAML too: the user edits either
    throw InputError(path, LineOf(image_node), std::string("its image: ") + e.what(), "fix or re-export the image");
  }
  grid.width = img.width;
  grid.height = img.height;
  grid.cells.assign(std::size_t(img.width) * img.height, -1);
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x) {
      const std::size_t i = std::size_t(y) * img.width + x;
      double shade = img.shade[i];
      const bool has_alpha = !img.alpha.empty();
      // nav2 averages alpha with the three colour channels in trinary mode.
      if (mode == RosMapMode::kTrinary && has_alpha) shade = (3.0 * shade + img.alpha[i]) / 4.0;
      const double occ = negate ? shade : 1.0 - shade;
      std::int8_t cell = -1;
      switch (mode) {
        case RosMapMode::kTrinary:
          cell = occupied_thresh < occ ? 100 : occ < free_thresh ? 0 : -1;
          break;
        case RosMapMode::kScale:
          if (has_alpha && img.alpha[i] < 1.0) cell = -1;
          else if (occupied_thresh < occ) cell = 100;
          else if (occ < free_thresh) cell = 0;
          else cell = static_cast<std::int8_t>(std::rint((occ - free_thresh) / (occupied_thresh - free_thresh) * 100.0));
          break;
        case RosMapMode::kRaw: {
          const double v = std::round(shade * 255);
          cell = v <= 100 ? static_cast<std::int8_t>(v) : -1;
          break;
        }
      }
      grid.cells[std::size_t(img.height - 1 - y) * img.width + x] = cell;
    }
  return grid;
}

}  // namespace slambox
