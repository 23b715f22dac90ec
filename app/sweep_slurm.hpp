#pragma once
// An sbatch script for a Slurm job array whose tasks each run one shard of a sweep
// (never one task per run: MaxArraySize defaults to 1001 and sites cap job counts).
#include <string>
#include <vector>

namespace slambox {

struct SlurmOptions {
  std::string sweep_file;     ///< absolute path
  std::string out_dir;        ///< absolute path, on a file system every node sees
  std::string slambox_exe;    ///< absolute path
  int shards = 8;             ///< array tasks
  int cpus_per_task = 2;      ///< also the shard's -j
  std::string time_limit = "04:00:00";
  std::string partition;      ///< empty = the site default
  std::vector<std::string> plugins;  ///< `--plugin` files (absolute), passed to every task
};

/// The script: `sbatch job.sh` submits the array; after it, `slambox sweep --merge DIR`
/// (or the dependent job the script's comment shows) writes the summary.
std::string SlurmArrayScript(const SlurmOptions& options);

}  // namespace slambox
