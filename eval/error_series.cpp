#include "eval/error_series.hpp"

#include "core/error.hpp"
#include "eval/statistics.hpp"

namespace slambox {

namespace {
using nlohmann::json;

json NumberArray(const std::vector<double>& v) {
  json a = json::array();
  for (double x : v) a.push_back(NumberOrNull(x));
  return a;
}

std::vector<double> NumbersOf(const json& j, const char* key) {
  std::vector<double> out;
  if (!j.is_object() || !j.contains(key) || !j.at(key).is_array()) return out;
  for (const auto& v : j.at(key)) out.push_back(v.is_number() ? v.get<double>() : NAN);
  return out;
}
}  // namespace

json ToJson(const ErrorSeries& s) {
  json j;
  j["t_s"] = NumberArray(s.t_s);
  j["distance_m"] = NumberArray(s.distance_m);
  j["ate_m"] = NumberArray(s.ate_m);
  j["heading_error_deg"] = NumberArray(s.heading_error_deg);
  j["nees"] = NumberArray(s.nees);
  j["nees_band_95"] = {s.nees_band_lo, s.nees_band_hi};
  j["rpe"] = {{"distance_m", NumberArray(s.rpe_distance_m)},
              {"trans_m", NumberArray(s.rpe_trans_m)},
              {"rot_deg", NumberArray(s.rpe_rot_deg)}};
  j["landmarks"] = json::array();
  for (const LandmarkError& l : s.landmarks)
    j["landmarks"].push_back(
        {{"id", l.id}, {"true_id", l.true_id}, {"error_m", NumberOrNull(l.error_m)}, {"nees", NumberOrNull(l.nees)}});
  return j;
}

ErrorSeries ErrorSeriesFromJson(const json& j, const std::string& path) {
  if (!j.is_object()) throw InputError(path, 0, "an error series is not a JSON object", "re-run `slambox run`");
  ErrorSeries s;
  s.t_s = NumbersOf(j, "t_s");
  s.distance_m = NumbersOf(j, "distance_m");
  s.ate_m = NumbersOf(j, "ate_m");
  s.heading_error_deg = NumbersOf(j, "heading_error_deg");
  s.nees = NumbersOf(j, "nees");
  const std::vector<double> band = NumbersOf(j, "nees_band_95");
  if (band.size() == 2) {
    s.nees_band_lo = band[0];
    s.nees_band_hi = band[1];
  }
  if (j.contains("rpe") && j.at("rpe").is_object()) {
    s.rpe_distance_m = NumbersOf(j.at("rpe"), "distance_m");
    s.rpe_trans_m = NumbersOf(j.at("rpe"), "trans_m");
    s.rpe_rot_deg = NumbersOf(j.at("rpe"), "rot_deg");
  }
  if (j.contains("landmarks") && j.at("landmarks").is_array())
    for (const auto& l : j.at("landmarks")) {
      if (!l.is_object() || !l.value("id", json()).is_number_integer() || !l.value("true_id", json()).is_number_integer())
        throw InputError(path, 0, "a landmark error needs integer id and true_id", "re-run `slambox run`");
      const json e = l.value("error_m", json()), n = l.value("nees", json());
      s.landmarks.push_back({l.at("id").get<int>(), l.at("true_id").get<int>(), e.is_number() ? e.get<double>() : NAN,
                             n.is_number() ? n.get<double>() : NAN});
    }
  return s;
}

}  // namespace slambox
