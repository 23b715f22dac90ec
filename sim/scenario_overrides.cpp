// `--set dotted.key=value`: the value is parsed as YAML and grafted onto the scenario's
// tree before validation, so an overridden value goes through exactly the same checks.
// List items are addressed by index (`world.landmarks.3.pos=[1, 2]`); a missing block is
// created (`sensors.gyro.rate_hz=100`); `sensors.lidar=null` removes a sensor.
#include "core/error.hpp"
#include "sim/scenario_yaml.hpp"

namespace slambox::scenario_detail {
namespace {

std::vector<std::string> SplitDots(const std::string& key) {
  std::vector<std::string> parts;
  std::size_t start = 0;
  while (true) {
    const std::size_t dot = key.find('.', start);
    parts.push_back(key.substr(start, dot - start));
    if (dot == std::string::npos) return parts;
    start = dot + 1;
  }
}

bool ParseIndex(const std::string& text, std::size_t& index) {
  if (text.empty() || text.find_first_not_of("0123456789") != std::string::npos || text.size() > 9) return false;
  index = std::stoul(text);
  return true;
}

void ApplyOne(YAML::Node& root, const std::string& text, YamlSource& src) {
  const std::string where = src.file + " (--set " + text + ")";
  const std::size_t eq = text.find('=');
  if (eq == std::string::npos || eq == 0)
    throw InputError(where, 0, "an override must look like key=value", "write e.g. --set robot.laps=3");
  const std::string key = text.substr(0, eq);
  const std::string value_text = text.substr(eq + 1);
  if (key.rfind("algo.", 0) == 0)
    throw InputError(where, 0, "'" + key + "' is an algorithm parameter, not a scenario key",
                     "pass it to `slambox run` / `slambox sweep`, which apply algo.* keys to the modules");
  YAML::Node value;
  try {
    value = YAML::Load(value_text);
  } catch (const YAML::Exception& e) {
    throw InputError(where, 0, "the value '" + value_text + "' is not valid YAML: " + e.msg,
                     "quote it or write a number, true/false, [x, y] or {key: value}");
  }

  const std::vector<std::string> parts = SplitDots(key);
  YAML::Node cur = root;
  std::string schema;  // "sensors.lidar", list items as '#'
  std::string done;    // the key so far, as the user wrote it
  for (std::size_t i = 0; i < parts.size(); ++i) {
    const std::string& part = parts[i];
    const bool last = i + 1 == parts.size();
    const std::vector<std::string>* keys = ScenarioKeysAt(schema);
    const std::string label = done.empty() ? "the top level" : "'" + done + "'";
    std::string next_schema;
    if (keys) {
      bool known = false;
      for (const auto& k : *keys) known = known || k == part;
      if (!known)
        throw InputError(where, 0, "unknown scenario key '" + key + "': " + label + " has no key '" + part + "'",
                         "use one of: " + JoinKeys(*keys));
      if (!cur.IsMap())
        throw InputError(where, 0, "cannot set '" + key + "': " + label + " in " + src.file + " is not a mapping",
                         "set the whole block instead, e.g. --set " + done + "={...}");
      next_schema = schema.empty() ? part : schema + "." + part;
      if (last) {
        cur[part] = value;
      } else {
        if (!cur[part].IsDefined() || cur[part].IsNull()) {
          if (!ScenarioKeysAt(next_schema))
            throw InputError(where, 0, "'" + (done.empty() ? part : done + "." + part) + "' is not in the scenario",
                             "set the whole value instead, e.g. --set " + (done.empty() ? part : done + "." + part) + "=[...]");
          cur[part] = YAML::Node(YAML::NodeType::Map);
        }
        cur.reset(cur[part]);
      }
    } else if (cur.IsSequence()) {
      std::size_t index = 0;
      if (!ParseIndex(part, index) || index >= cur.size())
        throw InputError(where, 0, "'" + done + "' is a list of " + std::to_string(cur.size()) + " items; '" + part +
                                       "' is not an index into it",
                         "use an index 0.." + std::to_string(cur.size() == 0 ? 0 : cur.size() - 1) +
                             " or set the whole list, e.g. --set " + done + "=[...]");
      next_schema = schema + ".#";
      if (last) {
        cur[index] = value;
      } else {
        cur.reset(cur[index]);
      }
    } else {
      throw InputError(where, 0, "unknown scenario key '" + key + "': '" + done + "' is a value, it has no key '" + part + "'",
                       "set '" + done + "' itself, e.g. --set " + done + "=VALUE");
    }
    schema = next_schema;
    done = done.empty() ? part : done + "." + part;
  }
  src.overrides.emplace_back(value, where);
}

}  // namespace

void ApplyOverrides(YAML::Node& root, const std::vector<std::string>& overrides, YamlSource& src) {
  if (overrides.empty()) return;
  if (!root.IsMap()) return;  // the parser reports the broken file first
  for (const auto& text : overrides) ApplyOne(root, text, src);
}

}  // namespace slambox::scenario_detail
