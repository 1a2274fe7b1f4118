#!/usr/bin/env bash
# Installs every build and test dependency of objscan through Debian packages (Debian 12).
# Idempotent: packages already present are left alone. Run as root.
# Optional peers: OBJSCAN_WITH_PEERS=1 also installs Open3D (C++ for objscan_bench, Python for the test
# that reads a run's PLY files with Open3D).
set -euo pipefail

packages=(
  build-essential cmake pkg-config git
  libeigen3-dev libembree-dev libpcl-dev liboctomap-dev libboost-graph-dev
  libassimp-dev libtinyxml2-dev libyaml-cpp-dev nlohmann-json3-dev libcli11-dev libpng-dev zlib1g-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  # objscan view bundles three.js into view.html; its test screenshots the page in headless Chromium.
  libjs-three chromium
  # Sanitizer pass and libFuzzer targets (scripts/test.sh --sanitize, scripts/fuzz.sh): clang, and
  # compiler-rt, which on Debian 12 holds the ASan/UBSan runtimes and libclang_rt.fuzzer used by
  # -fsanitize=fuzzer (libfuzzer-14-dev only adds a standalone libFuzzer.a, not needed).
  clang libclang-rt-dev
  # Sweet Home 3D's furniture catalogs (.sh3f): `objscan db build --models sweethome3d`.
  sweethome3d-furniture
  # The Python module (python/, pybind11) for the system python3, and numpy for its arrays.
  pybind11-dev python3-dev python3-numpy
  # scripts/slurm/bench_array.sh is tested on a one-node cluster the test starts (slurmctld + slurmd).
  slurm-wlm
  # objscan_ros (ros/, OBJSCAN_WITH_ROS): ROS 1 as Debian packages it: roscpp, tf2 and the message
  # packages the nodes speak; the master (roscore) and rosbag (record, and the Python reader) for the
  # end-to-end test. No catkin: the nodes build with objscan's CMake.
  ros-core-dev libroscpp-dev libtf2-ros-dev libsensor-msgs-dev libnav-msgs-dev libvisualization-msgs-dev
  libgeometry-msgs-dev libstd-msgs-dev ros-core python3-rosbag
)
if [[ "${OBJSCAN_WITH_PEERS:-0}" == "1" ]]; then
  packages+=(libopen3d-dev python3-open3d)
fi

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if [[ ${#missing[@]} -eq 0 ]]; then
  echo "install_deps: all ${#packages[@]} packages already installed"
  exit 0
fi

if [[ $(id -u) -ne 0 ]]; then
  echo "install_deps: missing packages (${missing[*]}); run this script as root" >&2
  exit 1
fi

echo "install_deps: installing ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
apt-get update -qq
apt-get install -y -qq --no-install-recommends "${missing[@]}"
