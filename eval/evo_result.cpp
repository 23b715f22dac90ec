#include "eval/evo_result.hpp"

#include <cmath>

#include "core/npy.hpp"
#include "eval/statistics.hpp"

namespace slambox {

namespace {

using nlohmann::json;

// evo's title: str(APE) plus the alignment line of main_ape.
std::string Title(AlignMode align) {
  const std::string base = "APE w.r.t. translation part (m)\n";
  switch (align) {
    case AlignMode::kSE2: return base + "(with SE(3) Umeyama alignment)";
    case AlignMode::kOrigin: return base + "(with origin alignment)";
    case AlignMode::kNone: break;
  }
  return base + "(not aligned)";
}

}  // namespace

std::vector<ZipEntry> EvoApeResultEntries(const Evaluation& ev, AlignMode align, const EvoResultNames& names) {
  const std::vector<double>& errors = ev.series.ate_m;
  const std::vector<double>& t = ev.series.t_s;
  const std::vector<double>& distance = ev.series.distance_m;
  std::vector<double> from_start(t.size());
  for (size_t i = 0; i < t.size(); ++i) from_start[i] = t[i] - t.front();
  const ErrorStatistics s = ComputeStatistics(errors);
  const json info = {{"title", Title(align)}, {"ref_name", names.ref_name}, {"est_name", names.est_name},
                     {"label", "APE (m)"}};
  // json.dumps writes NaN for an empty array's statistics; nlohmann writes null (evo_res shows None).
  const json stats = {{"rmse", NumberOrNull(s.rmse)}, {"mean", NumberOrNull(s.mean)},   {"median", NumberOrNull(s.median)},
                      {"std", NumberOrNull(s.std)},   {"min", NumberOrNull(s.min)},     {"max", NumberOrNull(s.max)},
                      {"sse", NumberOrNull(s.sse)}};
  std::vector<ZipEntry> entries = {{"info.json", info.dump()},
                                   {"stats.json", stats.dump()},
                                   {"error_array.npz", NpyFloat64(errors)},
                                   {"timestamps.npz", NpyFloat64(t)},
                                   {"seconds_from_start.npz", NpyFloat64(from_start)},
                                   {"distances_from_start.npz", NpyFloat64(distance)}};
  if (const auto& a = ev.metrics.alignment_se2; align == AlignMode::kSE2 && a) {
    const double x = (*a)[0], y = (*a)[1], th = (*a)[2] * M_PI / 180.0;
    const double c = std::cos(th), sn = std::sin(th);
    entries.push_back({"alignment_transformation_sim3.npz",
                       NpyFloat64Matrix({c, -sn, 0, x, sn, c, 0, y, 0, 0, 1, 0, 0, 0, 0, 1}, 4, 4)});
  }
  return entries;
}

void WriteEvoApeResult(const std::string& zip_path, const Evaluation& ev, AlignMode align, const EvoResultNames& names) {
  WriteZipStored(zip_path, EvoApeResultEntries(ev, align, names));
}

}  // namespace slambox
