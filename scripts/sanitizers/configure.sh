#!/usr/bin/env bash
# Configures the instrumented build folder (default build-sanitize/) shared by the sanitizer pass
# (scripts/test.sh --sanitize) and the libFuzzer targets (scripts/fuzz.sh), so that CI compiles the
# instrumented code once: clang, RelWithDebInfo (-O2 -g1), -fsanitize=address,undefined, and
# -DOBJSCAN_FUZZ=ON (libFuzzer's coverage feedback in every file, the fuzz_* programs).
# Benchmarks are off; so is the Python module (an instrumented extension cannot be loaded into the
# uninstrumented python3).
set -euo pipefail
cd "$(dirname "$0")/../.."
build=${1:-build-sanitize}
if ! command -v clang++ >/dev/null; then
  echo "configure.sh: clang++ not found: run scripts/install_deps.sh" >&2
  exit 1
fi
# Without the ROS nodes: roscpp is not instrumented, and the nodes' own logic is the ROS-free bridge
# (ros/bridge/), whose tests run here; the Release pass runs the nodes end to end (ros.e2e).
cmake -S . -B "${build}" -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=RelWithDebInfo \
      -DOBJSCAN_SANITIZE=address,undefined -DOBJSCAN_FUZZ=ON -DOBJSCAN_BUILD_BENCH=OFF -DOBJSCAN_BUILD_PYTHON=OFF \
      -DOBJSCAN_WITH_ROS=OFF
