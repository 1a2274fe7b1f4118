#!/usr/bin/env bash
# Builds objscan's libFuzzer targets (clang, -DOBJSCAN_FUZZ=ON: -fsanitize=fuzzer,address,undefined)
# into build-sanitize/, the sanitizer pass's folder (scripts/sanitizers/configure.sh), and runs them.
# See fuzz/fuzz_input.h for the targets and docs/reliability.md.
#
#   scripts/fuzz.sh TARGET [EXECS]   run one target for EXECS executions (default 10000)
#   scripts/fuzz.sh --all [EXECS]    every target in turn (what CI runs, with the default)
#   scripts/fuzz.sh --build          build only
#
# Targets: gazebo_world scene_file ply model_database config scannet bag.
# Seeds: fuzz/corpus/TARGET/ (read only); what the fuzzer adds: build-sanitize/corpus/TARGET/;
# a dictionary of the format's words, where there is one: fuzz/dict/TARGET.dict.
# A crash, timeout or out-of-memory is written to build-sanitize/findings/TARGET/ and fails the script;
# replay one with build-sanitize/fuzz/fuzz_TARGET FILE. Each run prints one summary line (executions,
# seconds, libFuzzer's cov: and ft: figures) and keeps libFuzzer's log in build-sanitize/logs/TARGET.log.
# Environment: FUZZ_TIMEOUT_S (wall s per input, default 10), FUZZ_RSS_MB (default 2048), FUZZ_MAX_LEN
# (bytes, default 8192), FUZZ_MAX_TOTAL_TIME_S (stop a target after this long, default 0: no limit),
# FUZZ_SEED (libFuzzer's -seed; default 0: a new one each run), OBJSCAN_JOBS (build jobs, default every
# core). libFuzzer's slow-unit-* files (inputs that took over 10 s of wall time without timing out) are
# kept beside the findings but are not findings.
set -euo pipefail
cd "$(dirname "$0")/.."
root=$(pwd)
build=${root}/build-sanitize
targets=(gazebo_world scene_file ply model_database config scannet bag)
jobs=${OBJSCAN_JOBS:-$(nproc 2>/dev/null || echo 2)}

usage() {
  sed -n '2,21p' "$0" | sed 's/^# \{0,1\}//'
  exit 2
}

build_fuzzers() {
  if ! command -v clang++ >/dev/null; then
    echo "fuzz.sh: clang++ not found: run scripts/install_deps.sh" >&2
    exit 1
  fi
  ./scripts/sanitizers/configure.sh "${build}" >/dev/null
  cmake --build "${build}" --target objscan_fuzzers -j"${jobs}"
}

run_target() {
  local target=$1 execs=$2
  local binary=${build}/fuzz/fuzz_${target}
  [[ -x "${binary}" ]] || { echo "fuzz.sh: unknown target '${target}' (one of: ${targets[*]})" >&2; exit 2; }
  mkdir -p "${build}/corpus/${target}" "${build}/findings/${target}" "${build}/logs"
  local log=${build}/logs/${target}.log
  local start end status=0
  local dict=()
  [[ -f "${root}/fuzz/dict/${target}.dict" ]] && dict=(-dict="${root}/fuzz/dict/${target}.dict")
  start=$(date +%s.%N)
  # Findings are found by the sanitizers (halting), by libFuzzer (timeout, rss/malloc limit) and by
  # the harness's contract (an escaped exception or a bad error message aborts).
  ASAN_OPTIONS="halt_on_error=1:detect_leaks=1" UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1" \
  LSAN_OPTIONS="suppressions=${root}/scripts/sanitizers/lsan.supp:print_suppressions=0" \
    "${binary}" -runs="${execs}" -timeout="${FUZZ_TIMEOUT_S:-10}" -rss_limit_mb="${FUZZ_RSS_MB:-2048}" \
      -max_len="${FUZZ_MAX_LEN:-8192}" -max_total_time="${FUZZ_MAX_TOTAL_TIME_S:-0}" -seed="${FUZZ_SEED:-0}" "${dict[@]}" -print_final_stats=1 -artifact_prefix="${build}/findings/${target}/" \
      "${build}/corpus/${target}" "${root}/fuzz/corpus/${target}" >"${log}" 2>&1 || status=$?
  end=$(date +%s.%N)
  local done_line cov ft runs
  done_line=$(grep -E '^#[0-9]+[[:space:]]+(DONE|pulse|NEW|REDUCE|INITED)' "${log}" | tail -1 || true)
  cov=$(sed -n 's/.* cov: \([0-9]*\).*/\1/p' <<<"${done_line}")
  ft=$(sed -n 's/.* ft: \([0-9]*\).*/\1/p' <<<"${done_line}")
  runs=$(sed -n 's/^stat::number_of_executed_units: *//p' "${log}" | tail -1)
  local findings
  findings=$(find "${build}/findings/${target}" -type f ! -name 'slow-unit-*' | wc -l)
  printf 'fuzz %-15s executions %-9s seconds %-8s cov %-6s ft %-6s findings %s%s\n' "${target}" "${runs:-?}" \
         "$(awk -v a="${start}" -v b="${end}" 'BEGIN { printf "%.1f", b - a }')" "${cov:-?}" "${ft:-?}" "${findings}" \
         "$([[ ${status} -ne 0 ]] && echo "  FAILED (exit ${status}; see ${log})")"
  if [[ ${status} -ne 0 ]]; then
    grep -E 'ERROR: |SUMMARY: |contract violated|Test unit written' "${log}" | head -8 >&2 || true
    return 1
  fi
}

[[ $# -ge 1 ]] || usage
case "$1" in
  -h|--help) usage ;;
  --build) build_fuzzers; exit 0 ;;
  --all)
    execs=${2:-10000}
    build_fuzzers
    failed=0
    for t in "${targets[@]}"; do run_target "${t}" "${execs}" || failed=1; done
    exit ${failed}
    ;;
  *)
    target=$1
    execs=${2:-10000}
    build_fuzzers
    run_target "${target}" "${execs}"
    ;;
esac
