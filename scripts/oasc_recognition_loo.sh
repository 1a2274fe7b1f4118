#!/usr/bin/env bash
# Model-disjoint recognition on the OASC dev worlds in minutes, without scanning rooms: for each world,
# `objscan db eval` recognises the world's own models (scanned from 1 and 3 views) against the
# database of the other worlds' models that a model-disjoint bench built.
#
#   scripts/oasc_recognition_loo.sh BENCH_OUT OUT [--set key=value ...]
#
# BENCH_OUT: the output folder of `objscan bench --suite oasc-dev --db-from-worlds` (its db/worlds/*.db
# are the model-disjoint databases; a bench killed after its databases were built is enough).
# OUT: one JSON per world (resumable) and a summary on stdout (scripts/recognition_summary.py): top-1 over
# the queries whose category is not `other` (whole from 1 and 3 views, pieces), per category and as named,
# by the best model alone and by the classifier alone.
# --set overrides recognition options (e.g. recognition.shortlist_size=60).
# Environment: OBJSCAN (the binary, default build/objscan), OBJSCAN_SHARED (default ../shared),
# OBJSCAN_JOBS (threads per eval, default every core).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
if [[ $# -lt 2 ]]; then
  sed -n '2,15p' "$0" | sed 's/^# \{0,1\}//'
  exit 2
fi
bench=$1
out=$2
shift 2
objscan=${OBJSCAN:-${root}/build/objscan}
shared=${OBJSCAN_SHARED:-${root}/../shared}
threads=${OBJSCAN_JOBS:-0}
[[ -x "${objscan}" ]] || { echo "oasc_recognition_loo.sh: ${objscan} not found: build first" >&2; exit 1; }
shopt -s nullglob
dbs=("${bench}"/db/worlds/*.db)
[[ ${#dbs[@]} -gt 0 ]] || { echo "oasc_recognition_loo.sh: no ${bench}/db/worlds/*.db (run a --db-from-worlds bench)" >&2; exit 1; }
mkdir -p "${out}"
for db in "${dbs[@]}"; do
  w=$(basename "${db}" .db)  # e.g. SUNCG-bathroom-0a2f...-0_3
  IFS=- read -r source category hash room <<< "${w}"
  world=${shared}/data/oasc-dev/${source}/${category}/${hash}/${room}/room.world
  [[ -f "${world}" ]] || { echo "oasc_recognition_loo.sh: ${world} not found" >&2; exit 1; }
  [[ -f "${out}/${w}.json" ]] && continue
  echo "oasc_recognition_loo.sh: ${w}" >&2
  "${objscan}" db eval --db "${db}" --queries "${world}" --model-path "${shared}/data/gazebo-models" \
    --queries-per-category 0 --threads "${threads}" "$@" > "${out}/${w}.json.tmp" 2> "${out}/${w}.err"
  mv "${out}/${w}.json.tmp" "${out}/${w}.json"
done
python3 "${root}/scripts/recognition_summary.py" "${out}"/*.json
