#!/usr/bin/env bash
# Runs `objscan bench` on a Slurm cluster: a job array of N shards (`objscan bench --shard i/N`, one
# array task each, all writing to the same OUT on a shared file system), then a merge job that starts
# when every shard has ended (afterany: a shard with a failed run still counts) and rebuilds the report
# over all shards with `objscan report OUT`. docs/cluster.md.
#
#   scripts/slurm/bench_array.sh --shards N --out OUT [options] -- BENCH_ARGS...
#
#   --shards N        array tasks (shard i/N each; default 4)
#   --out OUT         the bench folder, on a file system every node sees (required)
#   --objscan PATH    the objscan program the jobs run (default: `objscan` on PATH, made absolute)
#   --cpus N          CPUs per array task, passed to sbatch and as `objscan bench --jobs N` (default 1)
#   --time T          time limit of each array task (sbatch --time; default: the partition's)
#   --wait            block until the merge job has ended; exit with its status
#   --sbatch ARGS     more sbatch options for every job (quoted as one word: --sbatch "-p long -A me")
#   BENCH_ARGS        the rest of the `objscan bench` command: --suite NAME|DIR (required), --methods,
#                     --db, --seeds, --set, ... (not --out, --shard or --jobs: this script sets them)
#
# Prints one JSON line: {"array_job": ID, "merge_job": ID, "out": OUT, "shards": N}. The array
# task's log is OUT/slurm/shard-<i>.log, the merge job's OUT/slurm/merge.log; the merged report is
# OUT/report/ (results.md, results.json, ...). Without --db, every shard uses the built-in database
# from the cache ($OBJSCAN_CACHE_DIR or ~/.cache/objscan); build it once before (any `objscan run`),
# or pass --db, so the shards do not all build it at once.
#
# The same file is the job script: sbatch runs it with `__shard` or `__merge` as the first argument.
set -euo pipefail

die() { echo "bench_array.sh: $*" >&2; exit 2; }

if [[ "${1:-}" == "__shard" ]]; then
  shift
  objscan=$1 out=$2 shards=$3 cpus=$4
  shift 4
  : "${SLURM_ARRAY_TASK_ID:?__shard runs as a Slurm array task}"
  echo "bench_array.sh: shard ${SLURM_ARRAY_TASK_ID}/${shards} on $(hostname) (job ${SLURM_JOB_ID:-?})" >&2
  exec "$objscan" bench --out "$out" --shard "${SLURM_ARRAY_TASK_ID}/${shards}" --jobs "$cpus" "$@"
fi
if [[ "${1:-}" == "__merge" ]]; then
  shift
  objscan=$1 out=$2
  echo "bench_array.sh: merging $out on $(hostname) (job ${SLURM_JOB_ID:-?})" >&2
  exec "$objscan" report "$out" --out "$out/report"
fi

shards=4
out=""
objscan=""
cpus=1
time_limit=""
wait_merge=0
extra_sbatch=""
while [[ $# -gt 0 ]]; do
  case "$1" in
    --shards) shards=${2:?}; shift 2 ;;
    --out) out=${2:?}; shift 2 ;;
    --objscan) objscan=${2:?}; shift 2 ;;
    --cpus) cpus=${2:?}; shift 2 ;;
    --time) time_limit=${2:?}; shift 2 ;;
    --wait) wait_merge=1; shift ;;
    --sbatch) extra_sbatch=${2:?}; shift 2 ;;
    --) shift; break ;;
    -h|--help) sed -n '2,/^set -euo/p' "$0" | sed '$d' | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) break ;;
  esac
done
bench_args=("$@")

[[ -n "$out" ]] || die "--out OUT is required (a folder every node sees)"
[[ "$shards" =~ ^[1-9][0-9]*$ ]] || die "--shards '$shards': expected a positive integer"
[[ "$cpus" =~ ^[1-9][0-9]*$ ]] || die "--cpus '$cpus': expected a positive integer"
has_suite=0
for a in "${bench_args[@]}"; do
  case "$a" in
    --suite|--suite=*) has_suite=1 ;;
    --out|--out=*|--shard|--shard=*|--jobs|--jobs=*) die "'$a' is set by this script; give --out, --shards and --cpus to it instead" ;;
  esac
done
[[ $has_suite -eq 1 ]] || die "the bench arguments need --suite NAME|DIR (after --)"
command -v sbatch > /dev/null || die "sbatch not found: this script needs a Slurm cluster"
if [[ -z "$objscan" ]]; then
  objscan=$(command -v objscan) || die "objscan not on PATH: give --objscan PATH"
fi
[[ -x "$objscan" ]] || die "--objscan '$objscan': not an executable file"
objscan=$(realpath "$objscan")
self=$(realpath "$0")
mkdir -p "$out/slurm"
out=$(realpath "$out")

common=(--parsable --chdir "$out" --export ALL)
# shellcheck disable=SC2206  # --sbatch is a list of options on purpose
[[ -n "$extra_sbatch" ]] && common+=($extra_sbatch)
time_args=()
[[ -n "$time_limit" ]] && time_args=(--time "$time_limit")

array_job=$(sbatch "${common[@]}" "${time_args[@]}" --job-name objscan-bench --array "1-${shards}" \
  --cpus-per-task "$cpus" --output "$out/slurm/shard-%a.log" \
  "$self" __shard "$objscan" "$out" "$shards" "$cpus" "${bench_args[@]}")
array_job=${array_job%%;*}
wait_args=()
[[ $wait_merge -eq 1 ]] && wait_args=(--wait)
merge_job=$(sbatch "${common[@]}" "${wait_args[@]}" --job-name objscan-report --dependency "afterany:${array_job}" \
  --output "$out/slurm/merge.log" "$self" __merge "$objscan" "$out") || {
  status=$?
  echo "{\"array_job\": \"${array_job}\", \"merge_job\": \"${merge_job%%;*}\", \"out\": \"$out\", \"shards\": $shards, \"merge_status\": $status}"
  exit $status
}
merge_job=${merge_job%%;*}
echo "{\"array_job\": \"${array_job}\", \"merge_job\": \"${merge_job}\", \"out\": \"$out\", \"shards\": $shards}"
