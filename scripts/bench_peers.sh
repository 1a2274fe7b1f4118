#!/usr/bin/env bash
# objscan's hot stages against their peers, measured in one objscan_bench run, and the ratios:
# fusion of a depth frame (Open3D's ScalableTSDFVolume), binary PLY write and read of 2^20 points
# (Open3D's point-cloud I/O), FPFH at 200 keypoints (PCL's FPFHEstimation).
#
#   OBJSCAN_WITH_PEERS=1 ./scripts/install_deps.sh && ./scripts/build.sh    # objscan_bench with Open3D
#   ./scripts/bench_peers.sh [OUT.json]                                     # default: bench-peers.json
#
# Each benchmark is repeated (OBJSCAN_BENCH_REPETITIONS, default 5); the table gives the median CPU
# time of each and the peer / objscan ratio of the medians (> 1: objscan is faster). Every stage runs
# on one thread (OMP_NUM_THREADS=1 for Open3D's OpenMP loops; objscan's and PCL's are single-threaded
# here), so CPU time compares the work done and OpenMP's spinning threads do not inflate it.
set -euo pipefail
cd "$(dirname "$0")/.."
out=${1:-bench-peers.json}
bench=${OBJSCAN_BENCH:-build/objscan_bench}
[[ -x "${bench}" ]] || { echo "bench_peers.sh: ${bench} not found: build first (scripts/build.sh)" >&2; exit 1; }
if ! "${bench}" --benchmark_list_tests | grep -q Open3D; then
  echo "bench_peers.sh: ${bench} was built without Open3D: OBJSCAN_WITH_PEERS=1 ./scripts/install_deps.sh, then rebuild" >&2
  exit 1
fi
OMP_NUM_THREADS=${OMP_NUM_THREADS:-1} "${bench}" --benchmark_filter='^BM_(FuseFrame|FuseFrameRevisit|Open3DTsdfIntegrate|Open3DTsdfIntegrateRevisit|PlyWriteBinary|PlyReadBinary|Open3dPlyWriteBinary|Open3dPlyReadBinary|Fpfh)(/|$)' \
  --benchmark_repetitions="${OBJSCAN_BENCH_REPETITIONS:-5}" --benchmark_report_aggregates_only=true \
  --benchmark_out="${out}.tmp" --benchmark_out_format=json >&2
mv "${out}.tmp" "${out}"
python3 - "${out}" <<'PY'
import json, sys
runs = json.load(open(sys.argv[1]))
# The median of the repetitions, or the one run when there is a single repetition.
median = {b["run_name"]: b for b in runs["benchmarks"] if b.get("run_type") == "iteration"}
median.update({b["run_name"]: b for b in runs["benchmarks"] if b.get("aggregate_name") == "median"})
def ms(name):
    b = median[name]
    scale = {"ns": 1e-6, "us": 1e-3, "ms": 1.0, "s": 1e3}[b["time_unit"]]
    return b["cpu_time"] * scale
pairs = [
    ("fuse a depth frame into an empty map", "BM_FuseFrame", "BM_Open3DTsdfIntegrate", "Open3D ScalableTSDFVolume"),
    ("fuse it again (map holds it)", "BM_FuseFrameRevisit", "BM_Open3DTsdfIntegrateRevisit", "Open3D ScalableTSDFVolume"),
    ("write binary PLY, 2^20 points + normals", "BM_PlyWriteBinary/1048576", "BM_Open3dPlyWriteBinary/1048576", "Open3D WritePointCloud"),
    ("read binary PLY, 2^20 points + normals", "BM_PlyReadBinary/1048576", "BM_Open3dPlyReadBinary/1048576", "Open3D ReadPointCloud"),
    ("FPFH, 200 keypoints", "BM_Fpfh/pcl:0", "BM_Fpfh/pcl:1", "PCL FPFHEstimation"),
]
print(f"| stage | objscan (ms CPU) | peer | peer (ms CPU) | peer / objscan |")
print(f"|---|---|---|---|---|")
for what, ours, theirs, peer in pairs:
    if ours not in median or theirs not in median:
        print(f"| {what} | missing | {peer} | missing | - |")
        continue
    a, b = ms(ours), ms(theirs)
    print(f"| {what} | {a:.1f} | {peer} | {b:.1f} | {b / a:.2f} |")
ctx = runs["context"]
repetitions = max(b.get("repetitions", 0) for b in runs["benchmarks"])
print(f"\n{ctx.get('num_cpus')} CPUs at {ctx.get('mhz_per_cpu')} MHz, {ctx.get('date')}; medians of {repetitions} repetitions")
PY
