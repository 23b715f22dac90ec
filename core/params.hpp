#pragma once
// Named access to the fields of a module's config struct, so every field is settable as
// `--set algo.NAME.FIELD=VALUE` and listed by `slambox algorithms --params NAME`.
// A module binds each field once, with its unit, meaning and allowed values:
//   void BindParams(EkfSlamConfig& c, ParamBinder& b) {
//     b.Bind("gate_accept_chi2", c.gate_accept_chi2, "chi2", "accept the nearest landmark", Above(0));
//     b.Bind("association", c.association, kAssociationNames, "data association");
//   }
// The binder parses the text, checks the range (Validate, once per built config, as Ceres'
// Options::IsValid) and writes every error message, naming `--set algo.NAME.FIELD`.
#include <cstddef>
#include <functional>
#include <map>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "core/range.hpp"

namespace slambox {

struct ParamInfo {
  std::string name;
  std::string type;           ///< "double", "int", "bool", "enum"
  std::string default_value;  ///< the value at bind time, as text (shortest round-trip for a double)
  std::string unit;           ///< for an enum: its names, "a|b|c"
  std::string meaning;
};

/// FIELD -> VALUE text, from `--set algo.NAME.FIELD=VALUE`.
using ParamOverrides = std::map<std::string, std::string>;

/// Every value of an enum with its user-facing name, e.g. {{IcpMetric::kPointToLine, "point-to-line"}, ...}.
template <typename Enum>
using EnumNames = std::vector<std::pair<Enum, const char*>>;

/// The name of `value` in `names` ("?" if it is not listed: a bug).
template <typename Enum>
const char* NameOf(const EnumNames<Enum>& names, Enum value) {
  for (const auto& [v, n] : names)
    if (v == value) return n;
  return "?";
}

class ParamBinder {
 public:
  void Bind(const std::string& name, double& field, const std::string& unit, const std::string& meaning,
            Range range = {});
  void Bind(const std::string& name, int& field, const std::string& unit, const std::string& meaning,
            Range range = {});
  void Bind(const std::string& name, bool& field, const std::string& unit, const std::string& meaning);
  /// An enum field, set by one of its names.
  template <typename Enum>
  void Bind(const std::string& name, Enum& field, const EnumNames<Enum>& names, const std::string& meaning) {
    EnumField e;
    for (const auto& [v, n] : names) e.names.push_back(n);
    e.get = [&field, names] { return std::string(NameOf(names, field)); };
    e.set = [&field, names](std::size_t i) { field = names[i].first; };
    BindEnum(name, std::move(e), meaning);
  }

  /// Sets the bound fields from text. Throws InputError naming `--set algo.MODULE.FIELD` for
  /// an unknown field or a value that does not parse.
  void Apply(const ParamOverrides& overrides, const std::string& module) const;
  /// Throws InputError naming `--set algo.MODULE.FIELD` for the first bound number outside
  /// its range (a default or a value set by Apply).
  void Validate(const std::string& module) const;
  const std::vector<ParamInfo>& List() const { return infos_; }

 private:
  struct EnumField {
    std::vector<std::string> names;
    std::function<std::string()> get;
    std::function<void(std::size_t)> set;
  };
  void BindEnum(const std::string& name, EnumField field, const std::string& meaning);
  using FieldRef = std::variant<double*, int*, bool*, EnumField>;
  std::vector<ParamInfo> infos_;
  std::vector<FieldRef> fields_;
  std::vector<Range> ranges_;
};

}  // namespace slambox
