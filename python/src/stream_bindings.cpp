// slambox.Stream: a simulated or recorded stream, its header as a dict and its events as
// NumPy arrays (each built in one pass over the events, then cached).
#include <algorithm>
#include <cmath>
#include <limits>

#include "core/stream_io.hpp"
#include "bindings.hpp"

namespace slambox::python {
namespace {

using Array = py::array_t<double>;

template <class Event>
std::size_t Count(const Stream& s) {
  return static_cast<std::size_t>(
      std::count_if(s.events.begin(), s.events.end(), [](const SensorEvent& e) { return std::holds_alternative<Event>(e); }));
}

py::object OdometryArray(const Stream& s) {
  Array a({Count<OdometryEvent>(s), std::size_t{4}});
  double* out = a.mutable_data();
  for (const auto& e : s.events)
    if (const auto* o = std::get_if<OdometryEvent>(&e)) {
      *out++ = o->t_s;
      *out++ = o->delta.x;
      *out++ = o->delta.y;
      *out++ = o->delta.theta;
    }
  return std::move(a);
}

py::object GyroArray(const Stream& s) {
  Array a({Count<GyroEvent>(s), std::size_t{2}});
  double* out = a.mutable_data();
  for (const auto& e : s.events)
    if (const auto* g = std::get_if<GyroEvent>(&e)) {
      *out++ = g->t_s;
      *out++ = g->yaw_rate_rps;
    }
  return std::move(a);
}

py::object LandmarkArray(const Stream& s) {
  std::size_t n = 0;
  for (const auto& e : s.events)
    if (const auto* l = std::get_if<LandmarkEvent>(&e)) n += l->observations.size();
  Array a({n, std::size_t{4}});
  double* out = a.mutable_data();
  for (const auto& e : s.events)
    if (const auto* l = std::get_if<LandmarkEvent>(&e))
      for (const auto& o : l->observations) {
        *out++ = l->t_s;
        *out++ = o.range_m;
        *out++ = o.bearing_rad;
        *out++ = o.id;
      }
  return std::move(a);
}

/// times (M,), ranges (M, B), valid (M, B) with B the widest scan; a narrower scan (real
/// logs only) is padded with NaN ranges and valid = False.
py::tuple ScanArrays(const Stream& s) {
  std::size_t m = 0, beams = 0;
  for (const auto& e : s.events)
    if (const auto* l = std::get_if<LaserScanEvent>(&e)) {
      ++m;
      beams = std::max(beams, l->ranges_m.size());
    }
  Array times(m);
  Array ranges({m, beams});
  py::array_t<bool> valid({m, beams});
  double* t = times.mutable_data();
  double* r = ranges.mutable_data();
  bool* v = valid.mutable_data();
  for (const auto& e : s.events)
    if (const auto* l = std::get_if<LaserScanEvent>(&e)) {
      *t++ = l->t_s;
      const std::size_t n = l->ranges_m.size();
      std::copy(l->ranges_m.begin(), l->ranges_m.end(), r);
      std::fill(r + n, r + beams, std::numeric_limits<double>::quiet_NaN());
      for (std::size_t i = 0; i < beams; ++i) v[i] = i < n && l->valid[i] != 0;
      r += beams;
      v += beams;
    }
  return py::make_tuple(std::move(times), std::move(ranges), std::move(valid));
}

py::object GroundTruthArray(const Stream& s) {
  Array a({s.groundtruth.size(), std::size_t{4}});
  double* out = a.mutable_data();
  for (const auto& p : s.groundtruth) {
    *out++ = p.t_s;
    *out++ = p.pose.x;
    *out++ = p.pose.y;
    *out++ = p.pose.theta;
  }
  return std::move(a);
}

py::object Cached(StreamHandle& h, const std::string& key, py::object (*make)(const Stream&)) {
  auto it = h.cache.find(key);
  if (it == h.cache.end()) it = h.cache.emplace(key, make(*h.stream)).first;
  return it->second;
}

py::object ScanPart(StreamHandle& h, int index) {
  if (!h.cache.count("scans")) h.cache.emplace("scans", ScanArrays(*h.stream));
  return h.cache.at("scans").cast<py::tuple>()[index];
}

}  // namespace

void BindStream(py::module_& m) {
  py::class_<StreamHandle, std::shared_ptr<StreamHandle>>(m, "Stream", R"doc(
A stream of sensor events and ground truth, as `slambox simulate` writes it.

Arrays are float64 NumPy arrays built in one bulk copy on first access, then cached:
  odometry     (N, 4)  [t_s, dx_m, dy_m, dtheta_rad]  (motion in the previous robot frame)
  scan_times   (M,)    [t_s]
  scan_ranges  (M, B)  [m]; invalid beams hold range_max_m (NaN pads narrower scans)
  scan_valid   (M, B)  bool
  landmarks    (L, 4)  one row per observation [t_s, range_m, bearing_rad, id] (id -1: unknown)
  gyro         (G, 2)  [t_s, yaw_rate_rps]
  groundtruth  (K, 4)  [t_s, x_m, y_m, theta_rad] at every simulator step
)doc")
      .def_static(
          "read",
          [](const std::string& path) {
            auto s = std::make_shared<Stream>();
            {
              py::gil_scoped_release release;
              *s = ReadStream(path);
            }
            return std::make_shared<StreamHandle>(StreamHandle{std::move(s), {}});
          },
          py::arg("path"), "Reads a stream file (raises slambox.InputError for a bad, truncated or corrupt file).")
      .def(
          "write",
          [](const StreamHandle& h, const std::string& path) {
            py::gil_scoped_release release;
            WriteStream(*h.stream, path);
          },
          py::arg("path"), "Writes the stream file atomically (temporary name, then rename); `slambox run` reads it.")
      .def_property_readonly(
          "header", [](StreamHandle& h) { return Cached(h, "header", [](const Stream& s) { return ToPython(StreamHeaderToJson(s.header)); }); },
          "The header as a dict (scenario_name, seed, dt_s, duration_s, start_pose, sensors, world, ...).")
      .def_property_readonly("odometry", [](StreamHandle& h) { return Cached(h, "odometry", OdometryArray); },
                             "(N, 4) [t_s, dx_m, dy_m, dtheta_rad]")
      .def_property_readonly("scan_times", [](StreamHandle& h) { return ScanPart(h, 0); }, "(M,) scan times [s]")
      .def_property_readonly("scan_ranges", [](StreamHandle& h) { return ScanPart(h, 1); }, "(M, beams) ranges [m]")
      .def_property_readonly("scan_valid", [](StreamHandle& h) { return ScanPart(h, 2); }, "(M, beams) bool validity")
      .def_property_readonly("landmarks", [](StreamHandle& h) { return Cached(h, "landmarks", LandmarkArray); },
                             "(L, 4) [t_s, range_m, bearing_rad, id], one row per observation")
      .def_property_readonly("gyro", [](StreamHandle& h) { return Cached(h, "gyro", GyroArray); }, "(G, 2) [t_s, yaw_rate_rps]")
      .def_property_readonly("groundtruth", [](StreamHandle& h) { return Cached(h, "groundtruth", GroundTruthArray); },
                             "(K, 4) [t_s, x_m, y_m, theta_rad]")
      .def_property_readonly("duration_s", [](const StreamHandle& h) { return h.stream->header.duration_s; })
      .def("__len__", [](const StreamHandle& h) { return h.stream->events.size(); }, "Number of sensor events.")
      .def("__repr__", [](const StreamHandle& h) {
        return "<slambox.Stream " + h.stream->header.scenario_name + " seed " + std::to_string(h.stream->header.seed) + ", " +
               std::to_string(h.stream->events.size()) + " events, " + std::to_string(h.stream->header.duration_s) + " s>";
      });
}

}  // namespace slambox::python
