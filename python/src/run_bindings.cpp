// slambox.run: replays a stream to registry modules (by name) and Python modules, scores
// each with the evaluator `slambox run` uses (app/run_modules), and returns the results.
#include <cmath>
#include <set>

#include "app/run_modules.hpp"
#include "core/error.hpp"
#include "bindings.hpp"

namespace slambox::python {
namespace {

struct AlgorithmResult {
  std::string name;
  std::string status;
  MetricsView metrics;
  std::optional<Estimate> estimate;
};

struct Results {
  py::dict header;  ///< scenario, seed, duration_s, distance_m (as in metrics.json)
  std::vector<std::shared_ptr<AlgorithmResult>> algorithms;
};

/// One entry of `algorithms`: a registry name (its module built by CreateModules) or a Python module.
struct Entry {
  std::string name;
  py::object python;  ///< a slambox.Module, or None
};

Results Run(const StreamHandle& handle, const py::list& algorithms, const py::dict& overrides,
            const std::string& relations) {
  const Stream& stream = *handle.stream;
  const Overrides split = SplitOverrides(SetArguments(overrides));
  if (!split.scenario.empty())
    throw InputError("overrides " + split.scenario.front(), 0, "scenario keys do not apply to a Stream",
                     "give them to slambox.load_scenario(), or write algo.NAME.FIELD");
  std::vector<Entry> entries;
  std::vector<std::string> builtin;
  for (const py::handle item : algorithms) {
    if (py::isinstance<py::str>(item)) {
      for (const auto& n : ResolveAlgorithms({item.cast<std::string>()}, stream.header.sensors, false,
                                             HasMap(stream.header.world))) {
        entries.push_back({n, py::none()});
        builtin.push_back(n);
      }
    } else if (py::isinstance<SlamModule>(item)) {
      const py::object name = py::getattr(item, "name", py::none());
      entries.push_back({name.is_none() ? py::str(item.get_type().attr("__name__")).cast<std::string>()
                                        : py::str(name).cast<std::string>(),
                         py::reinterpret_borrow<py::object>(item)});
    } else {
      throw py::type_error("algorithms: expected module names (str) or slambox.Module instances, got " +
                           py::repr(item).cast<std::string>());
    }
  }
  if (entries.empty()) throw InputError("algorithms", 0, "no algorithm to run", "give e.g. ['odometry']");
  std::set<std::string> seen;
  for (const auto& e : entries)
    if (!seen.insert(e.name).second)
      throw py::value_error("algorithms: '" + e.name + "' appears twice (give a Python module its own `name`)");
  std::vector<std::unique_ptr<SlamModule>> modules = CreateModules(builtin, split.algo);
  const EvalOptions options = RunEvalOptions(stream, relations);

  Results results;
  results.header["scenario"] = stream.header.scenario_name;
  results.header["seed"] = stream.header.seed;
  results.header["converted_log"] = IsConvertedLog(stream.header);  // as metrics.json: a log's seed means nothing
  results.header["duration_s"] = stream.header.duration_s;
  const double distance_m = GroundTruthDistance(stream.groundtruth);
  results.header["distance_m"] = std::isnan(distance_m) ? py::object(py::none()) : py::object(py::float_(distance_m));
  std::size_t next_builtin = 0;
  for (const auto& e : entries) {
    ModuleRun run;
    if (e.python.is_none()) {
      std::unique_ptr<SlamModule> module = std::move(modules[next_builtin++]);
      py::gil_scoped_release release;  // C++ modules need no Python
      run = ReplayAndScore(*module, stream, options);
    } else {
      run = ReplayAndScore(*e.python.cast<SlamModule*>(), stream, options);
    }
    auto r = std::make_shared<AlgorithmResult>();
    r->name = e.name;
    r->status = RunStatusName(run.metrics.status);
    r->metrics.values = ToPython(ToJson(run.metrics)).cast<py::dict>();
    r->estimate = std::move(run.estimate);
    results.algorithms.push_back(std::move(r));
  }
  return results;
}

}  // namespace

void BindRun(py::module_& m) {
  py::class_<AlgorithmResult, std::shared_ptr<AlgorithmResult>>(m, "AlgorithmResult",
                                                                "One module's outcome in slambox.run().")
      .def_readonly("name", &AlgorithmResult::name)
      .def_readonly("status", &AlgorithmResult::status, "ok, diverged or failed (as in metrics.json)")
      .def_readonly("metrics", &AlgorithmResult::metrics, "slambox.Metrics: metrics.json's entry")
      .def_readonly("estimate", &AlgorithmResult::estimate, "slambox.Estimate, None when the module failed")
      .def("__repr__", [](const AlgorithmResult& r) { return "<slambox.AlgorithmResult " + r.name + ": " + r.status + ">"; });

  py::class_<Results>(m, "Results", "slambox.run()'s results: results['icp-poseslam'].metrics.ate_rmse_m")
      .def_readonly("header", &Results::header, "scenario, seed, duration_s, distance_m")
      .def_property_readonly("names", [](const Results& r) {
        std::vector<std::string> names;
        for (const auto& a : r.algorithms) names.push_back(a->name);
        return names;
      })
      .def("__getitem__", [](const Results& r, const std::string& name) {
        for (const auto& a : r.algorithms)
          if (a->name == name) return a;
        throw py::key_error(name);
      })
      .def("__len__", [](const Results& r) { return r.algorithms.size(); })
      .def("__iter__", [](const Results& r) { return py::make_iterator(r.algorithms.begin(), r.algorithms.end()); },
           py::keep_alive<0, 1>());

  m.def("run", &Run, py::arg("stream"), py::arg("algorithms") = py::list(py::make_tuple("odometry")),
        py::arg("overrides") = py::dict(), py::arg("relations") = "", R"doc(
Replays `stream` to each module and scores it as `slambox run` does (the same metrics).
  algorithms  registry names (str, "all" expands) and/or slambox.Module instances, run in order
  overrides   {"algo.NAME.FIELD": value} as `--set` (scenario keys go to load_scenario)
  relations   a Kümmerle relations file: relation_* on it
A module that raises gets status "failed" with the exception's last traceback line as
metrics.reason; the others are unaffected. Bad names or overrides raise slambox.InputError.
)doc");
}

}  // namespace slambox::python
