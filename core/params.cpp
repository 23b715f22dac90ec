#include "core/params.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <sstream>

#include "core/error.hpp"

namespace slambox {

namespace {
std::string ToText(double v) {
  std::ostringstream s;
  s.precision(17);
  s << v;
  return s.str();
}
}  // namespace

void ParamBinder::Bind(const std::string& name, double& field, const std::string& unit,
                       const std::string& meaning) {
  infos_.push_back({name, "double", ToText(field), unit, meaning});
  fields_.emplace_back(&field);
  choices_.emplace_back();
}
void ParamBinder::Bind(const std::string& name, int& field, const std::string& unit,
                       const std::string& meaning) {
  infos_.push_back({name, "int", std::to_string(field), unit, meaning});
  fields_.emplace_back(&field);
  choices_.emplace_back();
}
void ParamBinder::Bind(const std::string& name, bool& field, const std::string& unit,
                       const std::string& meaning) {
  infos_.push_back({name, "bool", field ? "true" : "false", unit, meaning});
  fields_.emplace_back(&field);
  choices_.emplace_back();
}
void ParamBinder::Bind(const std::string& name, std::string& field, const std::vector<std::string>& choices,
                       const std::string& meaning) {
  std::string unit;
  for (const auto& c : choices) unit += (unit.empty() ? "" : "|") + c;
  infos_.push_back({name, "string", field, unit, meaning});
  fields_.emplace_back(&field);
  choices_.push_back(choices);
}

void ParamBinder::Apply(const ParamOverrides& overrides, const std::string& module) const {
  for (const auto& entry : overrides) {
    const std::string &key = entry.first, &text = entry.second;  // (clang 14 cannot capture bindings)
    auto it = std::find_if(infos_.begin(), infos_.end(), [&](const ParamInfo& p) { return p.name == key; });
    const std::string where = "--set algo." + module + "." + key;
    if (it == infos_.end()) {
      std::string names;
      for (const auto& p : infos_) names += (names.empty() ? "" : ", ") + p.name;
      throw InputError(where, 0, "'" + module + "' has no parameter '" + key + "'",
                       "use one of: " + (names.empty() ? std::string("(none)") : names) +
                           " (see `slambox algorithms --params " + module + "`)");
    }
    const size_t i = static_cast<size_t>(it - infos_.begin());
    auto bad = [&](const std::string& expect) {
      throw InputError(where, 0, "value '" + text + "' is not " + expect, "give " + expect);
    };
    if (auto* d = std::get_if<double*>(&fields_[i])) {
      double v = 0;
      auto [p, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
      if (ec != std::errc() || p != text.data() + text.size() || !std::isfinite(v)) bad("a finite number");
      **d = v;
    } else if (auto* n = std::get_if<int*>(&fields_[i])) {
      int v = 0;
      auto [p, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
      if (ec != std::errc() || p != text.data() + text.size()) bad("an integer");
      **n = v;
    } else if (auto* b = std::get_if<bool*>(&fields_[i])) {
      if (text == "true" || text == "1") **b = true;
      else if (text == "false" || text == "0") **b = false;
      else bad("true or false");
    } else if (auto* s = std::get_if<std::string*>(&fields_[i])) {
      const auto& ch = choices_[i];
      if (!ch.empty() && std::find(ch.begin(), ch.end(), text) == ch.end()) bad("one of " + it->unit);
      **s = text;
    }
  }
}

}  // namespace slambox
