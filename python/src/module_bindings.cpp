// slambox.Module: a SLAM module written in Python, replayed in process like the C++ ones
// (a pybind11 trampoline over core's SlamModule). Only the methods a subclass overrides
// are called. A Python exception ends that module's run with status "failed" and the
// traceback's last line as the reason (the other modules go on).
#include <stdexcept>

#include "core/slam_module.hpp"
#include "core/stream_io.hpp"
#include "bindings.hpp"

namespace slambox::python {
namespace {

class PyModule : public SlamModule {
 public:
  void Start(const StreamHeader& header) override {
    Call("start", [&] { return py::make_tuple(ToPython(StreamHeaderToJson(header))); });
  }
  void OnOdometry(const OdometryEvent& e) override {
    Call("on_odometry", [&] { return py::make_tuple(e.t_s, e.delta.x, e.delta.y, e.delta.theta); });
  }
  void OnLaserScan(const LaserScanEvent& e) override {
    Call("on_scan", [&] {
      const std::size_t n = e.ranges_m.size();
      py::array_t<double> ranges(n), angles(n);
      py::array_t<bool> valid(n);
      for (std::size_t i = 0; i < n; ++i) {
        ranges.mutable_data()[i] = e.ranges_m[i];
        valid.mutable_data()[i] = e.valid[i] != 0;
        angles.mutable_data()[i] = e.angle_min_rad + static_cast<double>(i) * e.angle_increment_rad;
      }
      return py::make_tuple(e.t_s, ranges, valid, angles);
    });
  }
  void OnLandmarks(const LandmarkEvent& e) override {
    Call("on_landmarks", [&] {
      py::array_t<double> obs({e.observations.size(), std::size_t{3}});
      double* out = obs.mutable_data();
      for (const auto& o : e.observations) {
        *out++ = o.range_m;
        *out++ = o.bearing_rad;
        *out++ = o.id;
      }
      return py::make_tuple(e.t_s, obs);
    });
  }
  void OnGyro(const GyroEvent& e) override {
    Call("on_gyro", [&] { return py::make_tuple(e.t_s, e.yaw_rate_rps); });
  }
  Estimate Finish() override {
    py::gil_scoped_acquire gil;
    const py::function finish = py::get_override(static_cast<const SlamModule*>(this), "finish");
    if (!finish) throw std::runtime_error("NotImplementedError: the module defines no finish()");
    try {
      const py::object result = finish();
      if (py::isinstance<Estimate>(result)) return result.cast<Estimate>();
      return EstimateFromArrays(result, py::none(), py::none());  // an (K, 4) array of poses
    } catch (py::error_already_set& e) {
      throw std::runtime_error(LastTracebackLine(e));
    }
  }

 private:
  template <class Args>
  void Call(const char* name, Args&& args) {
    py::gil_scoped_acquire gil;
    const py::function f = py::get_override(static_cast<const SlamModule*>(this), name);
    if (!f) return;  // not overridden: the base class ignores the event
    try {
      f(*args());
    } catch (py::error_already_set& e) {
      throw std::runtime_error(LastTracebackLine(e));
    }
  }
};

}  // namespace

void BindModule(py::module_& m) {
  py::class_<SlamModule, PyModule>(m, "Module", R"doc(
Base class of SLAM modules written in Python; pass instances to slambox.run(). Override
any of (units as in the stream):
  start(header)                         header: the stream header dict
  on_odometry(t_s, dx_m, dy_m, dtheta_rad)  motion in the previous robot frame
  on_scan(t_s, ranges_m, valid, angles_rad)  1-D arrays, angles in the robot frame
  on_landmarks(t_s, observations)       (n, 3) [range_m, bearing_rad, id]
  on_gyro(t_s, yaw_rate_rps)
  finish() -> Estimate, or an (K, 4) array [t_s, x_m, y_m, theta_rad]  (required)
The class attribute `name` names it in the results (default: the class name).
)doc")
      .def(py::init<>())
      .def("start", [](SlamModule&, const py::object&) {}, py::arg("header"))
      .def("on_odometry", [](SlamModule&, double, double, double, double) {})
      .def("on_scan", [](SlamModule&, double, const py::object&, const py::object&, const py::object&) {})
      .def("on_landmarks", [](SlamModule&, double, const py::object&) {})
      .def("on_gyro", [](SlamModule&, double, double) {})
      .def("finish", [](SlamModule&) -> py::object { throw py::type_error("a slambox.Module must define finish()"); });
}

}  // namespace slambox::python
