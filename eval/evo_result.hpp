#pragma once
// evo's result archive (`evo_ape ... --save_results FILE.zip`, read by `evo_res` through
// evo/tools/file_interface.py load_res_file): a ZIP holding
//   info.json   {"title", "ref_name", "est_name", "label"}   (metrics.APE.get_result)
//   stats.json  {"rmse", "mean", "median", "std", "min", "max", "sse"}
//   NAME.npz    one array each, as np.save writes it (.npy bytes; evo names them .npz and
//               reads every *.npz entry with np.load): error_array, timestamps,
//               seconds_from_start, distances_from_start (all shape (n,), float64), and
//               alignment_transformation_sim3 (4 x 4) when the estimate was aligned.
// The APE is translation only (evo's default pose relation), over the matched poses.
#include <string>
#include <vector>

#include "core/zip_archive.hpp"
#include "eval/evaluate.hpp"

namespace slambox {

struct EvoResultNames {
  std::string ref_name = "groundtruth";  ///< evo uses the file names
  std::string est_name = "estimate";
};

/// The archive's entries from an evaluation's per-pose series (t_s, ate_m, distance_m)
/// and the alignment that produced them.
std::vector<ZipEntry> EvoApeResultEntries(const Evaluation& evaluation, AlignMode align, const EvoResultNames& names);

/// Writes the archive atomically.
void WriteEvoApeResult(const std::string& zip_path, const Evaluation& evaluation, AlignMode align,
                       const EvoResultNames& names);

}  // namespace slambox
