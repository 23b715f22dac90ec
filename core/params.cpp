#include "core/params.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>

#include "core/error.hpp"

namespace slambox {

namespace {
std::string ToText(double v) {  // shortest text that reads back as v: 0.2, not 0.20000000000000001
  char buf[32];
  const auto [end, ec] = std::to_chars(buf, buf + sizeof buf, v);
  return ec == std::errc() ? std::string(buf, end) : std::string("?");
}

std::string Where(const std::string& module, const std::string& field) { return "--set algo." + module + "." + field; }
}  // namespace

void ParamBinder::Bind(const std::string& name, double& field, const std::string& unit, const std::string& meaning,
                       Range range) {
  infos_.push_back({name, "double", ToText(field), unit, meaning});
  fields_.emplace_back(&field);
  ranges_.push_back(range);
}
void ParamBinder::Bind(const std::string& name, int& field, const std::string& unit, const std::string& meaning,
                       Range range) {
  infos_.push_back({name, "int", std::to_string(field), unit, meaning});
  fields_.emplace_back(&field);
  ranges_.push_back(range);
}
void ParamBinder::Bind(const std::string& name, bool& field, const std::string& unit, const std::string& meaning) {
  infos_.push_back({name, "bool", field ? "true" : "false", unit, meaning});
  fields_.emplace_back(&field);
  ranges_.emplace_back();
}
void ParamBinder::BindEnum(const std::string& name, EnumField field, const std::string& meaning) {
  std::string names;
  for (const auto& n : field.names) names += (names.empty() ? "" : "|") + n;
  infos_.push_back({name, "enum", field.get(), names, meaning});
  fields_.emplace_back(std::move(field));
  ranges_.emplace_back();
}

void ParamBinder::Apply(const ParamOverrides& overrides, const std::string& module) const {
  for (const auto& entry : overrides) {
    const std::string &key = entry.first, &text = entry.second;  // (clang 14 cannot capture bindings)
    auto it = std::find_if(infos_.begin(), infos_.end(), [&](const ParamInfo& p) { return p.name == key; });
    const std::string where = Where(module, key);
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
    } else if (auto* e = std::get_if<EnumField>(&fields_[i])) {
      const auto at = std::find(e->names.begin(), e->names.end(), text);
      if (at == e->names.end()) bad("one of " + it->unit);
      e->set(static_cast<std::size_t>(at - e->names.begin()));
    }
  }
}

void ParamBinder::Validate(const std::string& module) const {
  for (size_t i = 0; i < fields_.size(); ++i) {
    double v = 0;
    std::string text;
    if (auto* d = std::get_if<double*>(&fields_[i])) v = **d, text = ToText(v);
    else if (auto* n = std::get_if<int*>(&fields_[i])) v = **n, text = std::to_string(**n);
    else continue;
    if (!InRange(ranges_[i], v))
      throw InputError(Where(module, infos_[i].name), 0, infos_[i].name + " = " + text + " is out of range",
                       "give a value " + Describe(ranges_[i]));
  }
}

}  // namespace slambox
