#pragma once
// Shared pieces of the Python module `slambox` (python/README.md): conversions between
// the C++ records and Python objects / NumPy arrays, and one Bind* function per file.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "core/estimate.hpp"
#include "core/stream.hpp"

namespace slambox::python {

namespace py = pybind11;

/// JSON -> Python (null -> None, objects -> dict in key order, arrays -> list).
py::object ToPython(const nlohmann::json& j);

/// "key=value" strings from a dict (the CLI's `--set` form; bools as true/false).
std::vector<std::string> SetArguments(const py::dict& overrides);

/// A stream shared with Python; its arrays are built on first access (one bulk copy each)
/// and cached, since the stream never changes once made.
struct StreamHandle {
  std::shared_ptr<const Stream> stream;
  std::map<std::string, py::object> cache;
};

/// A metrics.json entry whose keys read as attributes (`m.ate_rmse_m`; None where null).
struct MetricsView {
  py::dict values;
};

/// Trajectory (K, 4) [t, x, y, theta] of an array or Estimate; throws ValueError on bad shape
/// or a non-finite value.
Estimate EstimateFromArrays(const py::object& poses, const py::object& covariances, const py::object& landmarks);

/// "ValueError: message": the last line Python prints for the exception.
std::string LastTracebackLine(const py::error_already_set& e);

void BindStream(py::module_& m);
void BindEstimate(py::module_& m);
void BindModule(py::module_& m);
void BindRun(py::module_& m);
void BindSweep(py::module_& m);

}  // namespace slambox::python
