#pragma once
// Named access to the fields of a module's config struct, so every field is settable as
// `--set algo.NAME.FIELD=VALUE` and listed by `slambox algorithms --params NAME`.
// A module binds each field once, with its unit and meaning:
//   void BindParams(EkfSlamConfig& c, ParamBinder& b) {
//     b.Bind("gate_accept", c.gate_accept, "chi2", "Mahalanobis gate to accept a match");
//   }
#include <map>
#include <string>
#include <variant>
#include <vector>

namespace slambox {

struct ParamInfo {
  std::string name;
  std::string type;           ///< "double", "int", "bool", "string"
  std::string default_value;  ///< the value at bind time, as text
  std::string unit;
  std::string meaning;
};

/// FIELD -> VALUE text, from `--set algo.NAME.FIELD=VALUE`.
using ParamOverrides = std::map<std::string, std::string>;

class ParamBinder {
 public:
  void Bind(const std::string& name, double& field, const std::string& unit, const std::string& meaning);
  void Bind(const std::string& name, int& field, const std::string& unit, const std::string& meaning);
  void Bind(const std::string& name, bool& field, const std::string& unit, const std::string& meaning);
  /// A string field restricted to `choices` (e.g. a robust kernel's name).
  void Bind(const std::string& name, std::string& field, const std::vector<std::string>& choices,
            const std::string& meaning);

  /// Sets the bound fields from text. Throws InputError naming `module` for an unknown
  /// field or a value that does not parse.
  void Apply(const ParamOverrides& overrides, const std::string& module) const;
  const std::vector<ParamInfo>& List() const { return infos_; }

 private:
  using FieldRef = std::variant<double*, int*, bool*, std::string*>;
  std::vector<ParamInfo> infos_;
  std::vector<FieldRef> fields_;
  std::vector<std::vector<std::string>> choices_;
};

}  // namespace slambox
