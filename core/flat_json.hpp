#pragma once
// A strict parser for one flat JSON object per line: string keys, each value a number, a
// string, true/false/null or an array of numbers. Every answer of the exec protocol
// (docs/exec_protocol.md) has this shape; parsing it directly is ~10x cheaper than a
// general JSON document (the protocol's overhead target is 5 us per event). Python's
// json writes NaN and +-Infinity as bare tokens: they are read as non-finite numbers and
// flagged, so a diverged child is told apart from a garbled line.
#include <string>
#include <string_view>
#include <vector>

namespace slambox {

struct FlatValue {
  enum class Kind { kNumber, kString, kBool, kNull, kNumberArray };
  Kind kind = Kind::kNull;
  double number = 0.0;
  bool integer = false;     ///< a number written without fraction or exponent
  bool non_finite = false;  ///< a NaN/Infinity token (in the number or the array)
  bool boolean = false;
  std::string text;
  std::vector<double> numbers;
};

struct FlatObject {
  std::vector<std::pair<std::string, FlatValue>> members;  ///< in line order, keys unique
  const FlatValue* Find(std::string_view key) const {
    for (const auto& [k, v] : members)
      if (k == key) return &v;
    return nullptr;
  }
};

/// Parses `line` into `out` (cleared first); returns "" or what is wrong and where.
std::string ParseFlatObject(std::string_view line, FlatObject& out);

}  // namespace slambox
