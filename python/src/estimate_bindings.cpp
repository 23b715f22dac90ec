// slambox.Estimate (a module's trajectory, covariances and landmarks as arrays) and
// slambox.Metrics (a metrics.json entry read by attribute).
#include <cmath>

#include "bindings.hpp"

namespace slambox::python {
namespace {

using Array = py::array_t<double, py::array::c_style | py::array::forcecast>;

Array Shaped(const py::object& o, std::vector<py::ssize_t> shape, const char* what) {
  Array a = Array::ensure(o);
  if (!a) throw py::value_error(std::string(what) + ": expected a float array");
  bool ok = a.ndim() == static_cast<py::ssize_t>(shape.size());
  for (std::size_t i = 0; ok && i < shape.size(); ++i) ok = shape[i] < 0 || a.shape(i) == shape[i];
  if (!ok) {
    std::string want = "(";
    for (std::size_t i = 0; i < shape.size(); ++i) want += (i ? ", " : "") + (shape[i] < 0 ? std::string("n") : std::to_string(shape[i]));
    throw py::value_error(std::string(what) + ": expected shape " + want + ")");
  }
  return a;
}

}  // namespace

Estimate EstimateFromArrays(const py::object& poses, const py::object& covariances, const py::object& landmarks) {
  Estimate e;
  const Array p = Shaped(poses, {-1, 4}, "poses [t_s, x_m, y_m, theta_rad]");
  const auto pv = p.unchecked<2>();
  const py::ssize_t k = p.shape(0);
  e.trajectory.resize(static_cast<std::size_t>(k));
  for (py::ssize_t i = 0; i < k; ++i) {
    for (int c = 0; c < 4; ++c)
      if (!std::isfinite(pv(i, c))) throw py::value_error("poses: row " + std::to_string(i) + " is not finite");
    if (i > 0 && !(pv(i, 0) > pv(i - 1, 0)))
      throw py::value_error("poses: times must increase (row " + std::to_string(i) + ")");
    e.trajectory[i].t_s = pv(i, 0);
    e.trajectory[i].pose = SE2(pv(i, 1), pv(i, 2), pv(i, 3));
  }
  if (!covariances.is_none()) {
    const Array c = Shaped(covariances, {k, 3, 3}, "covariances (one 3x3 over x, y, theta per pose)");
    const auto cv = c.unchecked<3>();
    for (py::ssize_t i = 0; i < k; ++i) {
      for (int r = 0; r < 3; ++r)
        for (int q = 0; q < 3; ++q) e.trajectory[i].covariance(r, q) = cv(i, r, q);
      e.trajectory[i].has_covariance = e.trajectory[i].covariance.allFinite();
    }
  }
  if (!landmarks.is_none()) {
    const Array l = Shaped(landmarks, {-1, 3}, "landmarks [id, x_m, y_m]");
    const auto lv = l.unchecked<2>();
    for (py::ssize_t i = 0; i < l.shape(0); ++i) {
      LandmarkEstimate le;
      le.id = static_cast<int>(lv(i, 0));
      le.position = {lv(i, 1), lv(i, 2)};
      e.landmarks.push_back(le);
    }
  }
  return e;
}

void BindEstimate(py::module_& m) {
  py::class_<Estimate>(m, "Estimate", R"doc(
What a module yields: Estimate(poses, covariances=None, landmarks=None).
  poses        (K, 4) [t_s, x_m, y_m, theta_rad], times increasing (stream event times)
  covariances  (K, 3, 3) over (x, y, theta), NaN where the module gives none
  landmarks    (L, 3) [id, x_m, y_m]
)doc")
      .def(py::init(&EstimateFromArrays), py::arg("poses"), py::arg("covariances") = py::none(),
           py::arg("landmarks") = py::none())
      .def_property_readonly("poses", [](const Estimate& e) {
        py::array_t<double> a({e.trajectory.size(), std::size_t{4}});
        double* out = a.mutable_data();
        for (const auto& p : e.trajectory) {
          *out++ = p.t_s;
          *out++ = p.pose.x;
          *out++ = p.pose.y;
          *out++ = p.pose.theta;
        }
        return a;
      }, "(K, 4) [t_s, x_m, y_m, theta_rad]")
      .def_property_readonly("covariances", [](const Estimate& e) {
        py::array_t<double> a({e.trajectory.size(), std::size_t{3}, std::size_t{3}});
        double* out = a.mutable_data();
        for (const auto& p : e.trajectory)
          for (int r = 0; r < 3; ++r)
            for (int c = 0; c < 3; ++c) *out++ = p.has_covariance ? p.covariance(r, c) : std::nan("");
        return a;
      }, "(K, 3, 3) pose covariances, NaN where none")
      .def_property_readonly("landmarks", [](const Estimate& e) {
        py::array_t<double> a({e.landmarks.size(), std::size_t{3}});
        double* out = a.mutable_data();
        for (const auto& l : e.landmarks) {
          *out++ = l.id;
          *out++ = l.position.x();
          *out++ = l.position.y();
        }
        return a;
      }, "(L, 3) [id, x_m, y_m]")
      .def_property_readonly("landmark_covariances", [](const Estimate& e) {
        py::array_t<double> a({e.landmarks.size(), std::size_t{2}, std::size_t{2}});
        double* out = a.mutable_data();
        for (const auto& l : e.landmarks)
          for (int r = 0; r < 2; ++r)
            for (int c = 0; c < 2; ++c) *out++ = l.has_covariance ? l.covariance(r, c) : std::nan("");
        return a;
      }, "(L, 2, 2) landmark covariances, NaN where none")
      .def("__len__", [](const Estimate& e) { return e.trajectory.size(); });

  py::class_<MetricsView>(m, "Metrics", "One algorithm's metrics.json entry: attributes named as its keys, None where null.")
      .def("__getattr__", [](const MetricsView& mt, const std::string& key) -> py::object {
        if (mt.values.contains(key)) return mt.values[py::str(key)];
        throw py::attribute_error("no metric '" + key + "' (see Metrics.keys())");
      })
      .def("__getitem__", [](const MetricsView& mt, const std::string& key) -> py::object {
        if (mt.values.contains(key)) return mt.values[py::str(key)];
        throw py::key_error(key);
      })
      .def("__contains__", [](const MetricsView& mt, const std::string& key) { return mt.values.contains(key); })
      .def("keys", [](const MetricsView& mt) { return py::list(mt.values.attr("keys")()); })
      .def("to_dict", [](const MetricsView& mt) { return py::dict(mt.values); }, "A copy as a plain dict (as in metrics.json).")
      .def("__dir__", [](const MetricsView& mt) { return py::list(mt.values.attr("keys")()); })
      .def("__repr__", [](const MetricsView& mt) { return "<slambox.Metrics " + py::repr(mt.values).cast<std::string>() + ">"; });
}

}  // namespace slambox::python
