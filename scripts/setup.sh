#!/usr/bin/env bash
# Installs the Debian 12 packages slambox needs, only those missing. Idempotent.
# Runs apt-get as root, or through sudo when not root.
# --with-slurm also installs a single-node Slurm (for the job-array test); --with-browser
# Debian's chromium, with which a test opens the sweep report headless (scripts/test.sh
# asks for both; the demo needs neither).
set -euo pipefail
PACKAGES=(
  build-essential cmake pkg-config ccache
  libbox2d-dev libeigen3-dev libceres-dev libosmesa6-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  libyaml-cpp-dev nlohmann-json3-dev libcli11-dev libnanoflann-dev
  libpng-dev libfreetype-dev fonts-dejavu-core
  zlib1g-dev libbz2-dev  # compressed CARMEN logs (datasets/)
  libmrpt-slam-dev  # MRPT 2.5 peers (slam/mrpt/); pulls in its maps, obs, poses, random dev packages
  libmrpt-graphslam-dev  # MRPT 2.5's pose-graph SLAM (the mrpt-graphslam peer)
  python3-dev python3-pybind11 python3-numpy python3-pytest  # the Python module (python/) for /usr/bin/python3; numpy also reads evo archives in a test
  mrpt-common  # MRPT's own config_files/ (the peers' real-log settings come from them, slam/mrpt/README.md)
  clang-14 libfuzzer-14-dev  # scripts/fuzz.sh: libFuzzer harnesses of every reader (tests/fuzz/)
  python3  # /usr/bin/python3: the exec example (examples/python/), the plugin test compares results.csv rows
  time  # /usr/bin/time: peak RSS in bench/startup.sh
)
# MRPT's own applications (icp-slam, rbpf-slam, graphslam-engine), only for the cross-check
# in slam/mrpt/README.md: `--with-mrpt-apps`.
for flag in "$@"; do
  case "$flag" in
    --with-mrpt-apps) PACKAGES+=(mrpt-apps) ;;
    --with-slurm) PACKAGES+=(slurmctld slurmd slurm-client munge) ;;
    --with-browser) PACKAGES+=(chromium) ;;  # tests/render/report_browser_test.cpp
    *) echo "setup: unknown option $flag (use --with-mrpt-apps, --with-slurm, --with-browser)" >&2; exit 2 ;;
  esac
done
missing=()
for p in "${PACKAGES[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "setup: all ${#PACKAGES[@]} packages already installed"
  exit 0
fi
SUDO=""
if [ "$(id -u)" -ne 0 ]; then
  command -v sudo >/dev/null || { echo "setup: not root and no sudo; install: ${missing[*]}" >&2; exit 1; }
  SUDO="sudo"
fi
echo "setup: installing ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
