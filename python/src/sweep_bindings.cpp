// slambox.sweep / read_results / register / algorithms: the CLI's sweep (app/sweep_run:
// validation, lock, resume, forked runs, results.csv + summary.md + figures) driven from
// Python, with slambox.Module subclasses registered as modules that forked runs build.
#include <Python.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <map>
#include <sstream>

#include "app/registry.hpp"
#include "app/sweep_run.hpp"
#include "core/error.hpp"
#include "eval/results_table.hpp"
#include "bindings.hpp"

namespace slambox::python {
namespace {

/// name -> the Python class a registered module is built from (re-registering a name
/// replaces the class: the registry's ModuleInfo looks it up here at each create()).
std::map<std::string, py::object>& PythonClasses() {
  static auto* classes = new std::map<std::string, py::object>();  // never destroyed: outlives the interpreter
  return *classes;
}

/// Owns the Python instance and forwards to its trampoline (python/src/module_bindings.cpp).
class PythonOwned : public SlamModule {
 public:
  PythonOwned(py::object instance, SlamModule* module) : instance_(std::move(instance)), module_(module) {}
  ~PythonOwned() override {
    py::gil_scoped_acquire gil;
    instance_ = py::object();
  }
  void Start(const StreamHeader& h) override { module_->Start(h); }
  void OnOdometry(const OdometryEvent& e) override { module_->OnOdometry(e); }
  void OnLaserScan(const LaserScanEvent& e) override { module_->OnLaserScan(e); }
  void OnLandmarks(const LandmarkEvent& e) override { module_->OnLandmarks(e); }
  void OnGyro(const GyroEvent& e) override { module_->OnGyro(e); }
  Estimate Finish() override { return module_->Finish(); }

 private:
  py::object instance_;
  SlamModule* module_;
};

SensorNeeds NeedsOf(const py::object& cls, const std::string& name) {
  SensorNeeds needs;
  const py::object given = py::getattr(cls, "needs", py::none());
  if (given.is_none()) return needs;
  if (!py::isinstance<py::dict>(given))
    throw py::type_error(name + ".needs: expected a dict like {'lidar': True}");
  for (const auto& [k, v] : given.cast<py::dict>()) {
    const std::string key = py::str(k);
    bool* field = key == "odometry" ? &needs.odometry : key == "lidar" ? &needs.lidar
                : key == "landmarks" ? &needs.landmarks : key == "map" ? &needs.map : nullptr;
    if (!field) throw py::value_error(name + ".needs: unknown sensor '" + key + "' (use odometry, lidar, landmarks, map)");
    *field = v.cast<bool>();
  }
  return needs;
}

/// Registers `cls` (a slambox.Module subclass) under `name` (default: its `name`
/// attribute, else the class name); returns the name.
std::string Register(const py::object& cls, const py::object& name_arg) {
  const py::object base = py::module_::import("slambox").attr("Module");
  if (!PyType_Check(cls.ptr()) || !PyObject_IsSubclass(cls.ptr(), base.ptr()))
    throw py::type_error("slambox.register: expected a subclass of slambox.Module (the class, not an instance), got " +
                         py::repr(cls).cast<std::string>());
  const py::object attr = py::getattr(cls, "name", py::none());
  const std::string name = !name_arg.is_none() ? py::str(name_arg).cast<std::string>()
                         : py::isinstance<py::str>(attr) ? attr.cast<std::string>()
                                                          : py::str(cls.attr("__name__")).cast<std::string>();
  const SensorNeeds needs = NeedsOf(cls, name);
  const bool known = PythonClasses().count(name) > 0;
  if (!known) {
    ModuleInfo info;
    info.name = name;
    const py::object doc = py::getattr(cls, "__doc__", py::none());
    const std::string text = doc.is_none() ? std::string() : py::str(doc).cast<std::string>();
    const auto start = text.find_first_not_of(" \n\t");
    info.description = start == std::string::npos ? "Python module" : text.substr(start, text.find('\n', start) - start);
    info.needs = needs;
    info.params = [] { return std::vector<ParamInfo>{}; };
    info.create = [name](const ParamOverrides& overrides) -> std::unique_ptr<SlamModule> {
      if (!overrides.empty())
        throw InputError("algo." + name + "." + overrides.begin()->first, 0,
                         "the Python module '" + name + "' has no options",
                         "drop the key (give the class its settings as class attributes)");
      py::gil_scoped_acquire gil;
      try {
        py::object instance = PythonClasses().at(name)();
        SlamModule* module = instance.cast<SlamModule*>();
        return std::make_unique<PythonOwned>(std::move(instance), module);
      } catch (py::error_already_set& e) {
        throw std::runtime_error(name + "(): " + LastTracebackLine(e));
      }
    };
    RegisterModule(std::move(info), "Python class " + py::str(cls.attr("__qualname__")).cast<std::string>());
  }
  PythonClasses()[name] = cls;
  return name;
}

bool IsNumber(const std::string& text, double& value) {
  char* end = nullptr;
  value = std::strtod(text.c_str(), &end);
  return !text.empty() && end == text.c_str() + text.size();
}

py::object Number(double v) { return std::isnan(v) ? py::object(py::none()) : py::object(py::float_(v)); }

/// results.csv as a list of dicts (NaN cells -> None, numeric grid values -> float) or a
/// NumPy structured array (strings as 'U', numbers as float64 with NaN where empty).
py::object Table(const ResultsTable& t, bool as_array) {
  std::map<std::string, bool> numeric_grid;
  for (const auto& k : t.grid_keys) {
    bool all = true;
    double v = 0;
    for (const auto& r : t.rows)
      if (const std::string* s = GridValue(r, k); !s || !IsNumber(*s, v)) all = false;
    numeric_grid[k] = all;
  }
  if (!as_array) {
    py::list rows;
    for (const auto& r : t.rows) {
      py::dict d;
      d["run_id"] = r.run_id;
      d["scenario"] = r.scenario;
      d["seed"] = r.seed;
      d["algorithm"] = r.algorithm;
      d["status"] = r.status;
      for (const auto& k : t.grid_keys) {
        const std::string* s = GridValue(r, k);
        double v = 0;
        if (!s) d[py::str(k)] = py::none();
        else if (numeric_grid[k] && IsNumber(*s, v)) d[py::str(k)] = v;
        else d[py::str(k)] = *s;
      }
      for (const auto& k : t.metric_keys) {
        const auto it = r.metrics.find(k);
        d[py::str(k)] = Number(it == r.metrics.end() ? NAN : it->second);
      }
      rows.append(d);
    }
    return rows;
  }
  py::list fields, records;
  auto width = [&](auto get) {
    std::size_t w = 1;
    for (const auto& r : t.rows) w = std::max(w, get(r).size());
    return "U" + std::to_string(w);
  };
  fields.append(py::make_tuple("run_id", width([](const ResultRow& r) { return r.run_id; })));
  fields.append(py::make_tuple("scenario", width([](const ResultRow& r) { return r.scenario; })));
  fields.append(py::make_tuple("seed", "u8"));
  fields.append(py::make_tuple("algorithm", width([](const ResultRow& r) { return r.algorithm; })));
  fields.append(py::make_tuple("status", width([](const ResultRow& r) { return r.status; })));
  for (const auto& k : t.grid_keys)
    fields.append(py::make_tuple(k, numeric_grid[k] ? std::string("f8") : width([&](const ResultRow& r) {
      const std::string* s = GridValue(r, k);
      return s ? *s : std::string();
    })));
  for (const auto& k : t.metric_keys) fields.append(py::make_tuple(k, "f8"));
  for (const auto& r : t.rows) {
    py::list cells;
    cells.append(r.run_id);
    cells.append(r.scenario);
    cells.append(r.seed);
    cells.append(r.algorithm);
    cells.append(r.status);
    for (const auto& k : t.grid_keys) {
      const std::string* s = GridValue(r, k);
      double v = NAN;
      if (numeric_grid[k]) cells.append(s && IsNumber(*s, v) ? v : NAN);
      else cells.append(s ? *s : std::string());
    }
    for (const auto& k : t.metric_keys) {
      const auto it = r.metrics.find(k);
      cells.append(it == r.metrics.end() ? NAN : it->second);
    }
    records.append(py::tuple(cells));
  }
  const py::module_ np = py::module_::import("numpy");
  return np.attr("array")(records, py::arg("dtype") = np.attr("dtype")(fields));
}

py::object ReadResults(const std::string& path, bool as_array) {
  const std::string file = path.size() >= 4 && path.substr(path.size() - 4) == ".csv" ? path : path + "/results.csv";
  return Table(ReadResultsCsv(file), as_array);
}

py::object Sweep(const py::object& spec_arg, const std::string& out, int jobs, bool resume, bool figures,
                 const py::list& modules, double timeout_s, const std::string& shard, bool quiet, bool as_array) {
  for (const py::handle cls : modules) Register(py::reinterpret_borrow<py::object>(cls), py::none());
  SweepSpec spec;
  SweepRunOptions o;
  if (py::isinstance<py::dict>(spec_arg)) {
    // A dict is the sweep file's content; classes in `algorithms` are registered by name.
    py::dict d = py::module_::import("copy").attr("deepcopy")(spec_arg);
    if (d.contains("algorithms") && py::isinstance<py::list>(d["algorithms"])) {
      py::list names;
      for (const py::handle a : d["algorithms"].cast<py::list>())
        names.append(PyType_Check(a.ptr()) ? py::str(Register(py::reinterpret_borrow<py::object>(a), py::none()))
                                           : py::reinterpret_borrow<py::object>(a));
      d["algorithms"] = names;
    }
    // JSON is YAML: the same parser and checks as a sweep file; DIR/sweep.yaml keeps the text.
    o.spec_text = py::module_::import("json").attr("dumps")(d, py::arg("indent") = 1).cast<std::string>() + "\n";
    spec = ParseSweepSpec(o.spec_text, "sweep dict");
  } else {
    const std::string path = py::str(spec_arg);
    spec = LoadSweepSpec(path);
    std::stringstream text;
    text << std::ifstream(path).rdbuf();
    o.spec_text = text.str();
  }
  if (timeout_s > 0) spec.timeout_s = timeout_s;
  o.out_dir = out;
  o.plugins = spec.plugins;
  o.shard = shard;
  o.jobs = jobs;
  o.resume = resume;
  o.figures = figures;
  o.quiet = quiet;
  // The GIL stays held by this thread through the sweep, so a forked run (a copy of this
  // thread) holds it too and can call Python modules; Python's own fork protocol around it.
  o.fork_hooks = {PyOS_BeforeFork, PyOS_AfterFork_Parent, PyOS_AfterFork_Child};
  const SweepOutcome outcome = ExecuteSweep(spec, o);
  if (!outcome.summary_written) return py::none();
  return ReadResults(out, as_array);
}

}  // namespace

void BindSweep(py::module_& m) {
  m.def("register", &Register, py::arg("cls"), py::arg("name") = py::none(), R"doc(
Registers a slambox.Module subclass as a module named `name` (default: its `name`
attribute, else the class name), so sweeps and run() can name it like a C++ module; each
run builds a fresh instance with cls(). Class attributes: `needs` = {"lidar": True, ...}
(sensors it needs, as `slambox algorithms` shows; default odometry only), the docstring's
first line as its description. Registering the same name again replaces the class.
Returns the name.
)doc");
  m.def("sweep", &Sweep, py::arg("spec"), py::arg("out"), py::arg("jobs") = 0, py::arg("resume") = false,
        py::arg("figures") = false, py::arg("modules") = py::list(), py::arg("timeout_s") = 0.0,
        py::arg("shard") = "", py::arg("quiet") = true, py::arg("as_array") = false, R"doc(
Runs a sweep as `slambox sweep SPEC -o OUT` does (the same code): every scenario x grid
point x seed in its own forked process (`jobs` at a time, 0 = one per core), resumable
(`resume=True` skips finished runs), written as the CLI's sweep folder (OUT/runs/,
results.csv, timing.csv, summary.md; figures and report.html with figures=True).
  spec     a sweep file path, or a dict with the file's keys:
           {"scenarios": ["loop"], "algorithms": ["odometry", MyModule], "seeds": 3,
            "grid": {"sensors.lidar.sigma_range_m": [0.01, 0.05]}, "set": {...}}
           slambox.Module subclasses in "algorithms" are registered (slambox.register)
  modules  Module subclasses to register first (a sweep file names them by `name`)
  shard    "I/N": only that shard's runs (returns None; merge with `slambox sweep --merge OUT`)
Returns results.csv's rows (see read_results). Bad input raises slambox.InputError
before any run starts. The calling thread holds the GIL until the sweep ends.
)doc");
  m.def("read_results", &ReadResults, py::arg("path"), py::arg("as_array") = false, R"doc(
A sweep's results.csv (a sweep folder or the file): a list of dicts, one per run and
algorithm (run_id, scenario, seed, algorithm, status, each swept key, each metric; None
where a metric is null), or with as_array=True a NumPy structured array (NaN where null).
)doc");
  m.def(
      "algorithms",
      [] {
        py::list out;
        for (const auto& l : ListModules()) {
          py::dict d;
          d["name"] = l.name;
          d["description"] = l.description;
          d["origin"] = l.origin.empty() ? std::string("built-in") : l.origin;
          d["needs"] = py::dict(py::arg("odometry") = l.needs.odometry, py::arg("lidar") = l.needs.lidar,
                                py::arg("landmarks") = l.needs.landmarks, py::arg("map") = l.needs.map);
          d["unavailable"] = l.unavailable.empty() ? py::object(py::none()) : py::object(py::str(l.unavailable));
          d["in_all"] = l.in_all;  // false: run only when named, not by "all"
          out.append(d);
        }
        return out;
      },
      "Every module `slambox algorithms` lists (built-ins, plugins, registered Python classes), as dicts.");
}

}  // namespace slambox::python
