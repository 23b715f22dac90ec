#include "app/sweep_slurm.hpp"

#include <sstream>

namespace slambox {

namespace {
// Single-quote for sh: ' -> '\''
std::string Quote(const std::string& s) {
  std::string q = "'";
  for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}
}  // namespace

std::string SlurmArrayScript(const SlurmOptions& o) {
  std::ostringstream s;
  s << "#!/bin/bash\n"
    << "# slambox sweep as a Slurm job array: task I runs shard I/" << o.shards << ".\n"
    << "# Submit:  jobid=$(sbatch --parsable job.sh)\n"
    << "# Merge:   sbatch --dependency=afterany:$jobid --wrap " << Quote(o.slambox_exe + " sweep --merge " + o.out_dir) << "\n"
    << "#SBATCH --job-name=slambox-sweep\n"
    << "#SBATCH --array=0-" << (o.shards - 1) << "\n"
    << "#SBATCH --cpus-per-task=" << o.cpus_per_task << "\n"
    << "#SBATCH --time=" << o.time_limit << "\n"
    << "#SBATCH --output=" << o.out_dir << "/slurm/%A_%a.out\n";
  if (!o.partition.empty()) s << "#SBATCH --partition=" << o.partition << "\n";
  s << "set -euo pipefail\n"
    << "mkdir -p " << Quote(o.out_dir + "/slurm") << "\n"
    << "exec " << Quote(o.slambox_exe) << " sweep " << Quote(o.sweep_file) << " -o " << Quote(o.out_dir)
    << " --resume";
  for (const auto& p : o.plugins) s << " --plugin " << Quote(p);
  s << " --shard \"${SLURM_ARRAY_TASK_ID}/" << o.shards << "\" -j \"${SLURM_CPUS_PER_TASK:-"
    << o.cpus_per_task << "}\"\n";
  return s.str();
}

}  // namespace slambox
