#!/usr/bin/env bash
# Installs the Debian packages the harness needs (only those missing), then configures and
# builds it into build/. Idempotent and non-interactive; safe to run before every command.
#
#   scripts/setup.sh            install + build (Release, x86-64-v3)
#   RAPID_NATIVE=ON scripts/setup.sh    tune for this CPU instead (results then host-specific)
set -euo pipefail

here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build_dir=${RAPID_BUILD_DIR:-$here/build}

packages=(
  build-essential cmake git  # g++ brings OpenMP (libgomp, omp.h); no pkg-config lookup is made
  sumo                     # sumo, netconvert, libsumocpp and its headers
  sumo-tools               # SUMOConfig.cmake and SUMO_HOME (/usr/share/sumo: xsd schemas);
                           # only *recommended* by sumo, so --no-install-recommends skips it
  libeigen3-dev nlohmann-json3-dev libcli11-dev
  libhdf5-dev hdf5-tools   # HDF5 C++ API; h5dump for inspecting datasets
  libgtest-dev libgmock-dev libbenchmark-dev  # GTestConfig.cmake needs gmock
  python3 python3-matplotlib  # figures: scripts/plot runs Debian's /usr/bin/python3 (numpy
                              # comes with matplotlib)
  python3-pil              # Pillow, for matplotlib's GIF writer (animated figures)
  pybind11-dev python3-dev python3-numpy  # the Python module rapid_harness (docs/python.md)
  xvfb xauth libgl1-mesa-dri  # a headless X server with software OpenGL for the sumo-gui test
)
# Everything else the scripts and tests call is in every Debian root, even a minbase one:
# coreutils, bash, sed, grep, mawk, util-linux (runuser), hostname. The Slurm daemons
# (slurmctld slurmd slurm-client munge) are installed by scripts/slurm-local when it first
# starts a local Slurm, since only scripts/test-slurm needs them.
# scripts/test-fresh-machine checks on a fresh minbase bookworm that this list is enough.

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "setup: installing ${missing[*]}"
  sudo=""
  if [ "$(id -u)" -ne 0 ]; then
    command -v sudo >/dev/null || { echo "setup: need root or sudo to install: ${missing[*]}" >&2; exit 1; }
    sudo=sudo
  fi
  # `env` inside sudo: sudo resets the environment, and a DEBIAN_FRONTEND before it would be lost.
  $sudo apt-get update -qq
  $sudo env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
  echo "setup: packages installed"
fi

export SUMO_HOME=${SUMO_HOME:-/usr/share/sumo}
echo "setup: building $build_dir"
cmake -S "$here" -B "$build_dir" -DCMAKE_BUILD_TYPE=Release -DRAPID_NATIVE="${RAPID_NATIVE:-OFF}" >/dev/null
cmake --build "$build_dir" -j "$(nproc)"
echo "setup: built $build_dir/rapid"
