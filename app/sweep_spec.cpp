#include "app/sweep_spec.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include "core/error.hpp"
#include "core/file_status.hpp"
#include "core/limits.hpp"
#include "core/stream_io.hpp"
#include "core/version.hpp"
#include "eval/metrics.hpp"

namespace slambox {

namespace {

int Line(const YAML::Node& n) { return n.Mark().line + 1; }

std::vector<std::string> StringList(const YAML::Node& n, const std::string& file, const std::string& key) {
  if (!n.IsSequence() || n.size() == 0)
    throw InputError(file, Line(n), "'" + key + "' must be a non-empty list", "write e.g. " + key + ": [a, b]");
  std::vector<std::string> out;
  for (const auto& item : n) {
    if (!item.IsScalar()) throw InputError(file, Line(item), "'" + key + "' items must be names", "write plain names");
    out.push_back(item.Scalar());
  }
  return out;
}

std::string ScalarText(const YAML::Node& n, const std::string& file, const std::string& key) {
  if (n.IsScalar()) return n.Scalar();
  YAML::Emitter e;
  e << YAML::Flow << n;  // lists and maps as flow YAML, parsed back by the scenario loader
  if (!e.good()) throw InputError(file, Line(n), "cannot use the value of '" + key + "'", "give a scalar or a list");
  return e.c_str();
}

std::vector<std::string> SweptAndSetKeys(const SweepSpec& spec) {
  std::vector<std::string> keys;
  for (const auto& [k, v] : spec.fixed) keys.push_back(k);
  for (const auto& [k, v] : spec.grid) keys.push_back(k);
  return keys;
}

// check: {METRIC: {relative: R, absolute: A}} -> spec.check_tolerances (a `sweep --check` metric only).
void ParseCheckTolerances(const YAML::Node& check, const std::string& path, SweepSpec& spec) {
  const std::string example = "write check: {ate_rmse_m: {relative: 0.1, absolute: 0.001}}";
  if (!check.IsMap()) throw InputError(path, Line(check), "'check' must map metrics to tolerances", example);
  for (const auto& kv : check) {
    const std::string metric = kv.first.Scalar();
    const MetricDescriptor* d = FindMetric(metric);
    if (!d || !d->checked)
      throw InputError(path, Line(kv.first), "'" + metric + "' is not a metric that sweep --check compares",
                       "use a checked metric of eval/README.md (ate_*, rpe_*, landmark_rmse_m, anees, relation_*)");
    if (!kv.second.IsMap()) throw InputError(path, Line(kv.second), "the tolerance of '" + metric + "' must be a map", example);
    std::pair<double, double> tol{0.1, 0.0};
    for (const auto& t : kv.second) {
      const std::string key = t.first.Scalar();
      double* field = key == "relative" ? &tol.first : key == "absolute" ? &tol.second : nullptr;
      if (!field) throw InputError(path, Line(t.first), "unknown tolerance key '" + key + "'", "use relative, absolute");
      try {
        *field = t.second.as<double>();
      } catch (const YAML::BadConversion&) {
        *field = -1;
      }
      if (!(*field >= 0 && *field < 1e6))
        throw InputError(path, Line(t.second), key + " tolerance of '" + metric + "' must be a number >= 0", example);
    }
    spec.check_tolerances.emplace_back(metric, tol);
  }
}

}  // namespace

SweepSpec LoadSweepSpec(const std::string& path) {
  std::error_code ec;
  const auto bytes = std::filesystem::file_size(path, ec);
  if (ec || !std::filesystem::is_regular_file(path, ec))
    throw InputError(path, 0, "cannot open the sweep file", "check the path");
  if (bytes > limits::kMaxYamlFileBytes)
    throw InputError(path, 0,
                     "the sweep file has " + std::to_string(bytes) + " bytes, over the limit of " +
                         std::to_string(limits::kMaxYamlFileBytes),
                     "give a sweep YAML file (scenarios, algorithms, seeds, grid)");
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  if (!in) throw InputError(path, 0, "cannot read the sweep file", "check its permissions");
  return ParseSweepSpec(text.str(), path);
}

SweepSpec ParseSweepSpec(const std::string& text, const std::string& path) {
  YAML::Node root;
  try {
    root = YAML::Load(text);
  } catch (const YAML::ParserException& e) {
    throw InputError(path, e.mark.line + 1, "not valid YAML: " + e.msg, "fix the YAML syntax");
  }
  if (!root.IsMap()) throw InputError(path, 1, "a sweep file is a YAML map", "see DESIGN.md: scenarios, algorithms, seeds, grid");
  SweepSpec spec;
  spec.source = path;
  const std::set<std::string> known = {"scenarios", "algorithms", "seeds", "grid", "set", "timeout_s", "relations", "plugins", "check", "interval"};
  for (const auto& kv : root) {
    const std::string key = kv.first.Scalar();
    if (!known.count(key))
      throw InputError(path, Line(kv.first), "unknown key '" + key + "'",
                       "use scenarios, algorithms, seeds, grid, set, timeout_s, relations, plugins, check, interval");
  }
  for (const char* required : {"scenarios", "algorithms", "seeds"})
    if (!root[required]) throw InputError(path, 1, std::string("missing '") + required + "'", std::string("add ") + required + ":");
  spec.scenarios = StringList(root["scenarios"], path, "scenarios");
  spec.algorithms = StringList(root["algorithms"], path, "algorithms");
  const YAML::Node seeds = root["seeds"];
  try {
    if (seeds.IsScalar()) {
      const long n = seeds.as<long>();
      if (n < 1 || n > 100000) throw InputError(path, Line(seeds), "seeds must be 1..100000", "write e.g. seeds: 10");
      for (long s = 0; s < n; ++s) spec.seeds.push_back(static_cast<std::uint64_t>(s));
    } else if (seeds.IsSequence() && seeds.size() > 0) {
      for (const auto& s : seeds) spec.seeds.push_back(s.as<std::uint64_t>());
    } else {
      throw InputError(path, Line(seeds), "seeds must be a count or a non-empty list", "write seeds: 10 or seeds: [0, 3]");
    }
  } catch (const YAML::BadConversion&) {
    throw InputError(path, Line(seeds), "seeds must be non-negative integers", "write seeds: 10 or seeds: [0, 3]");
  }
  if (std::set<std::uint64_t>(spec.seeds.begin(), spec.seeds.end()).size() != spec.seeds.size())
    throw InputError(path, Line(seeds), "a seed is listed twice", "list each seed once");
  if (const YAML::Node grid = root["grid"]) {
    if (!grid.IsMap()) throw InputError(path, Line(grid), "'grid' must map keys to lists", "write grid: {robot.laps: [1, 2]}");
    for (const auto& kv : grid) {
      const std::string key = kv.first.Scalar();
      if (!kv.second.IsSequence() || kv.second.size() == 0)
        throw InputError(path, Line(kv.second), "grid key '" + key + "' needs a non-empty list of values",
                         "write " + key + ": [v1, v2]");
      std::vector<std::string> values;
      for (const auto& v : kv.second) values.push_back(ScalarText(v, path, key));
      spec.grid.emplace_back(key, values);
    }
  }
  if (const YAML::Node set = root["set"]) {
    if (!set.IsMap()) throw InputError(path, Line(set), "'set' must be a map of overrides", "write set: {robot.laps: 1}");
    for (const auto& kv : set) spec.fixed.emplace_back(kv.first.Scalar(), ScalarText(kv.second, path, kv.first.Scalar()));
  }
  if (const YAML::Node t = root["timeout_s"]) {
    try {
      spec.timeout_s = t.as<double>();
    } catch (const YAML::BadConversion&) {
      spec.timeout_s = -1;
    }
    if (!(spec.timeout_s > 0)) throw InputError(path, Line(t), "timeout_s must be a positive number", "write timeout_s: 600");
  }
  if (const YAML::Node iv = root["interval"]) {
    const std::string word = iv.IsScalar() ? iv.Scalar() : "";
    const auto method = IntervalMethodFromName(word);
    if (method) spec.interval = *method;
    else throw InputError(path, Line(iv), "interval must be auto, t or bootstrap, not '" + word + "'",
                       "write interval: auto (t from 10 seeds, bootstrap below), t or bootstrap");
  }
  if (const YAML::Node rel = root["relations"]) {
    if (!rel.IsMap())
      throw InputError(path, Line(rel), "'relations' must map scenario entries to relations files",
                       "write relations: {intel.stream: intel.relations}");
    for (const auto& kv : rel) {
      const std::string entry = kv.first.Scalar();
      if (std::find(spec.scenarios.begin(), spec.scenarios.end(), entry) == spec.scenarios.end())
        throw InputError(path, Line(kv.first), "relations for '" + entry + "', which is not in 'scenarios'",
                         "use the scenario entry exactly as listed in scenarios:");
      if (!kv.second.IsScalar() || !IsRegularFile(kv.second.Scalar()))
        throw InputError(path, Line(kv.second), "relations file '" + ScalarText(kv.second, path, entry) + "' not found",
                         "give the path of a relations file (relative to the working folder)");
      spec.relations.emplace_back(entry, kv.second.Scalar());
    }
  }
  if (const YAML::Node check = root["check"]) ParseCheckTolerances(check, path, spec);
  // A stream is already simulated: scenario overrides cannot apply to it.
  for (const auto& scenario : spec.scenarios) {
    if (!IsRegularFile(scenario) || !IsStreamFile(scenario)) continue;
    for (const auto& key : SweptAndSetKeys(spec))
      if (key.rfind("algo.", 0) != 0)
        throw InputError(path, 1, "'" + key + "' is a scenario key and '" + scenario + "' is a stream file",
                         "set only algo.NAME.FIELD keys in a sweep over streams, or list scenarios instead");
  }
  double runs = static_cast<double>(spec.scenarios.size()) * static_cast<double>(spec.seeds.size());
  for (const auto& [key, values] : spec.grid) runs *= static_cast<double>(values.size());
  if (runs > static_cast<double>(limits::kMaxSweepRuns))
    throw InputError(path, 0,
                     "the sweep asks for " + std::to_string(runs) + " runs (scenarios x grid points x seeds), over the limit of " +
                         std::to_string(limits::kMaxSweepRuns),
                     "split it into several sweeps, or use fewer grid values or seeds");
  if (const YAML::Node plugins = root["plugins"]) {
    const std::filesystem::path base = std::filesystem::path(path).parent_path();
    for (const auto& p : StringList(plugins, path, "plugins"))
      spec.plugins.push_back(std::filesystem::path(p).is_absolute() ? p : (base / p).lexically_normal().string());
  }
  return spec;
}

std::string RunId(const std::string& scenario, const std::vector<std::string>& sets, std::uint64_t seed,
                  const std::string& relations) {
  std::string canonical = std::string("slambox ") + kVersion + "\nscenario " + scenario + "\nseed " +
                          std::to_string(seed) + "\n";
  for (const auto& s : sets) canonical += "set " + s + "\n";
  if (!relations.empty()) canonical += "relations " + relations + "\n";
  std::uint64_t h = 1469598103934665603ull;  // FNV-1a 64
  for (unsigned char c : canonical) {
    h ^= c;
    h *= 1099511628211ull;
  }
  char buf[17];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(h));
  return buf;
}

std::vector<SweepRun> ExpandSweep(const SweepSpec& spec) {
  std::size_t points = 1;
  for (const auto& [key, values] : spec.grid) points *= values.size();
  std::vector<SweepRun> runs;
  for (const auto& scenario : spec.scenarios) {
    const bool is_stream = IsRegularFile(scenario) && IsStreamFile(scenario);
    std::string relations;
    for (const auto& [entry, file] : spec.relations)
      if (entry == scenario) relations = file;
    const std::vector<std::uint64_t> seeds = is_stream ? std::vector<std::uint64_t>{0} : spec.seeds;
    for (std::size_t p = 0; p < points; ++p) {
      // Mixed-radix digits of p, last grid key fastest.
      std::vector<std::pair<std::string, std::string>> values(spec.grid.size());
      std::size_t rest = p;
      for (std::size_t k = spec.grid.size(); k-- > 0;) {
        const auto& [key, options] = spec.grid[k];
        values[k] = {key, options[rest % options.size()]};
        rest /= options.size();
      }
      for (std::uint64_t seed : seeds) {
        SweepRun run;
        run.is_stream = is_stream;
        run.relations = relations;
        run.index = runs.size();
        run.scenario = scenario;
        run.seed = seed;
        run.grid_values = values;
        for (const auto& [k, v] : spec.fixed) run.sets.push_back(k + "=" + v);
        for (const auto& [k, v] : values) run.sets.push_back(k + "=" + v);
        run.id = RunId(scenario, run.sets, seed, relations);
        runs.push_back(std::move(run));
      }
    }
  }
  return runs;
}

}  // namespace slambox
