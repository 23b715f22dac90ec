// LoadScenario: resolve a built-in name or a file, parse the YAML, apply `--set`
// overrides on the tree, then validate fields and geometry.
#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/error.hpp"
#include "core/limits.hpp"
#include "sim/scenario_yaml.hpp"

namespace slambox {
using namespace scenario_detail;
namespace {

std::string BuiltinNames() {
  std::string names;
  for (const auto& e : EmbeddedScenarios()) names += (names.empty() ? "" : ", ") + std::string(e.name);
  return names;
}

/// {text, source label}: a regular file wins over a built-in of the same name.
std::pair<std::string, std::string> ReadScenarioText(const std::string& name_or_path) {
  std::error_code ec;
  if (std::filesystem::is_regular_file(name_or_path, ec)) {
    const auto bytes = std::filesystem::file_size(name_or_path, ec);
    if (!ec && bytes > limits::kMaxYamlFileBytes)
      throw InputError(name_or_path, 0,
                       "the scenario file has " + std::to_string(bytes) + " bytes, over the limit of " +
                           std::to_string(limits::kMaxYamlFileBytes),
                       "give a scenario YAML file (the built-in ones are a few kB)");
    std::ifstream in(name_or_path, std::ios::binary);
    std::ostringstream text;
    text << in.rdbuf();
    if (!in) throw InputError(name_or_path, 0, "cannot read the file", "check its permissions");
    return {text.str(), name_or_path};
  }
  for (const auto& e : EmbeddedScenarios())
    if (name_or_path == e.name) return {e.yaml, "builtin:" + name_or_path};
  if (std::filesystem::exists(name_or_path, ec))
    throw InputError(name_or_path, 0, "not a regular file", "give a scenario .yaml file or a built-in name");
  throw InputError(name_or_path, 0, "no such scenario file or built-in scenario",
                   "give a .yaml path or one of: " + BuiltinNames() + " (see `slambox scenarios`)");
}

}  // namespace

std::vector<BuiltinScenario> BuiltinScenarios() {
  std::vector<BuiltinScenario> out;
  for (const auto& e : EmbeddedScenarios()) {
    const YAML::Node root = YAML::Load(e.yaml);
    out.push_back({e.name, root["description"].IsDefined() ? root["description"].Scalar() : ""});
  }
  return out;
}

Scenario LoadScenario(const std::string& name_or_path, const std::vector<std::string>& overrides) {
  const auto [text, file] = ReadScenarioText(name_or_path);
  Scenario s = LoadScenarioText(text, file, overrides);
  if (s.name.empty()) s.name = std::filesystem::path(name_or_path).stem().string();
  return s;
}

Scenario LoadScenarioText(const std::string& text, const std::string& file, const std::vector<std::string>& overrides) {
  if (text.size() > limits::kMaxYamlFileBytes)
    throw InputError(file, 0,
                     "the scenario text has " + std::to_string(text.size()) + " bytes, over the limit of " +
                         std::to_string(limits::kMaxYamlFileBytes),
                     "give a scenario YAML file (the built-in ones are a few kB)");
  YamlSource src{file, {}};
  YAML::Node root;
  try {
    root = YAML::Load(text);
  } catch (const YAML::Exception& e) {
    throw InputError(file, e.mark.is_null() ? 0 : e.mark.line + 1, "not valid YAML: " + e.msg,
                     "fix the syntax (indentation, ':' after keys, matching brackets); see `slambox scenario show loop`");
  }
  ApplyOverrides(root, overrides, src);
  Scenario s = ParseScenario(root, src);
  CheckScenarioSize(s);
  CheckScenarioGeometry(s);
  return s;
}

}  // namespace slambox
