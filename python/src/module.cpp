// The Python module `slambox` (python/README.md): scenarios, simulation, streams as NumPy
// arrays, evaluation, runs of C++ and Python modules. The CLI's own code does the work;
// this file only converts arguments and results.
#include <dlfcn.h>

#include <cmath>
#include <filesystem>

#include "app/eval_options.hpp"
#include "app/plugins.hpp"
#include "core/error.hpp"
#include "core/tum.hpp"
#include "core/version.hpp"
#include "eval/evaluate.hpp"
#include "bindings.hpp"
#include "sim/scenario.hpp"
#include "sim/simulate.hpp"

namespace slambox::python {
namespace {

Estimate ReadEstimate(const py::object& o, const char* what) {
  if (py::isinstance<Estimate>(o)) return o.cast<Estimate>();
  if (py::isinstance<py::str>(o) || py::hasattr(o, "__fspath__")) {
    const std::string path = py::str(o).cast<std::string>();
    Estimate e;
    for (const auto& p : ReadTum(path)) e.trajectory.push_back({p.t_s, p.pose, Eigen::Matrix3d::Zero(), false});
    if (e.trajectory.empty()) throw InputError(path, 0, "no pose in the file", "give a non-empty TUM file");
    return e;
  }
  try {
    return EstimateFromArrays(o, py::none(), py::none());
  } catch (const py::value_error& e) {
    throw py::value_error(std::string(what) + ": " + e.what());
  }
}

MetricsView Evaluate(const py::object& gt, const py::object& est, const std::string& align, double delta,
                 const std::string& delta_unit, bool all_pairs, bool pairs_from_reference, double t_max_diff_s,
                 bool interpolate) {
  const EvalChoices choices{align, delta, delta_unit, all_pairs, pairs_from_reference, t_max_diff_s, interpolate};
  const EvalOptions options = TrajectoryEvalOptions(choices, OptionSpelling::kPython);  // cmd_eval's checks
  GroundTruth truth;
  for (const auto& p : ReadEstimate(gt, "gt").trajectory) truth.trajectory.push_back({p.t_s, p.pose});
  const Estimate estimate = ReadEstimate(est, "est");
  Metrics metrics;
  {
    py::gil_scoped_release release;
    metrics = EvaluateEstimate(truth, estimate, options).metrics;
  }
  RequireMatchedPoses(metrics, choices, "est", OptionSpelling::kPython);
  return MetricsView{ToPython(ToJson(metrics)).cast<py::dict>()};
}

Scenario LoadScenarioFrom(const std::string& name_or_path, const py::dict& overrides) {
  return LoadScenario(name_or_path, SetArguments(overrides));
}

std::shared_ptr<StreamHandle> SimulateScenario(const py::object& scenario, std::uint64_t seed) {
  const Scenario s = py::isinstance<Scenario>(scenario) ? scenario.cast<Scenario>()
                                                        : LoadScenario(py::str(scenario).cast<std::string>());
  auto stream = std::make_shared<Stream>();
  {
    py::gil_scoped_release release;
    *stream = Simulate(s, seed);
  }
  return std::make_shared<StreamHandle>(StreamHandle{std::move(stream), {}});
}

/// lib/slambox (renderer, shipped plugins) for this module: beside the build tree's
/// build/python/ (build/lib/slambox) or the install's PREFIX/lib/python3/dist-packages/
/// (PREFIX/lib/slambox); python3's own /proc/self/exe says nothing about either.
void FindSlamboxLibraryDir() {
  Dl_info info{};
  if (!dladdr(reinterpret_cast<void*>(&FindSlamboxLibraryDir), &info) || !info.dli_fname) return;
  const std::filesystem::path here = std::filesystem::path(info.dli_fname).parent_path();
  for (const auto& dir : {here.parent_path() / "lib" / "slambox", here.parent_path().parent_path() / "slambox"}) {
    std::error_code ec;
    if (std::filesystem::is_directory(dir, ec)) {
      SetSlamboxLibraryDir(dir.lexically_normal().string());
      return;
    }
  }
}

}  // namespace
}  // namespace slambox::python

PYBIND11_MODULE(slambox, m) {
  using namespace slambox;
  using namespace slambox::python;
  m.doc() = "slambox: simulate 2D SLAM streams, replay them to C++ or Python modules, evaluate (python/README.md).";
  m.attr("__version__") = kVersion;

  // InputError: the CLI's message (file:line: problem, fix), with .file and .line.
  static py::exception<InputError> input_error(m, "InputError", PyExc_ValueError);
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const InputError& e) {
      py::object error = py::reinterpret_borrow<py::object>(input_error.ptr())(e.what());
      error.attr("file") = e.file();
      error.attr("line") = e.line();
      PyErr_SetObject(input_error.ptr(), error.ptr());
    }
  });

  BindStream(m);
  BindEstimate(m);
  BindModule(m);
  BindRun(m);
  BindSweep(m);
  FindSlamboxLibraryDir();

  py::class_<Scenario>(m, "Scenario", "A validated scenario (slambox.load_scenario).")
      .def_readonly("name", &Scenario::name)
      .def_readonly("description", &Scenario::description)
      .def_readonly("duration_s", &Scenario::duration_s)
      .def_readonly("source", &Scenario::source, "file path or builtin:NAME")
      .def_property_readonly("yaml", &ScenarioToYaml, "The resolved scenario as YAML (`slambox scenario show`).")
      .def("__repr__", [](const Scenario& s) { return "<slambox.Scenario " + s.name + " from " + s.source + ">"; });

  m.def(
      "scenarios",
      [] {
        py::dict out;
        for (const auto& s : BuiltinScenarios()) out[py::str(s.name)] = s.description;
        return out;
      },
      "The built-in scenarios: {name: description}.");
  m.def("load_scenario", &LoadScenarioFrom, py::arg("name_or_path"), py::arg("overrides") = py::dict(), R"doc(
Loads a built-in scenario by name or a YAML file, applies overrides {"dotted.key": value}
(the CLI's --set) and validates it. Raises slambox.InputError (a ValueError) whose message
is the CLI's and whose .file and .line name the place.
)doc");
  m.def("simulate", &SimulateScenario, py::arg("scenario"), py::arg("seed") = 0,
        "Simulates a Scenario (or a scenario name / path) with `seed` -> Stream (as `slambox simulate`).");
  m.def("read_tum", [](const std::string& path) {
    std::vector<StampedPose> poses = ReadTum(path);
    py::array_t<double> a({poses.size(), std::size_t{4}});
    double* out = a.mutable_data();
    for (const auto& p : poses) {
      *out++ = p.t_s;
      *out++ = p.pose.x;
      *out++ = p.pose.y;
      *out++ = p.pose.theta;
    }
    return a;
  }, py::arg("path"), "A TUM trajectory file -> (K, 4) [t_s, x_m, y_m, theta_rad] (yaw from the quaternion).");
  m.def("evaluate", &Evaluate, py::arg("gt"), py::arg("est"), py::arg("align") = "none", py::arg("delta") = 1.0,
        py::arg("delta_unit") = "m", py::arg("all_pairs") = false, py::arg("pairs_from_reference") = false,
        py::arg("t_max_diff_s") = 0.01, py::arg("interpolate") = false, R"doc(
Scores an estimate against ground truth with evo's definitions, as `slambox eval` does.
  gt, est     (K, 4) arrays [t_s, x_m, y_m, theta_rad], TUM file paths, or (est) an Estimate
  align       "none" | "se2" (Umeyama, evo -a) | "origin" (evo --align_origin), for ate_*
  delta, delta_unit  RPE step: "m" metres, "f" frames, "d" degrees
Returns slambox.Metrics (the keys of `slambox eval --json`).
)doc");
}
