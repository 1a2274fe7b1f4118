#!/usr/bin/env bash
# Model-disjoint recognition on the OASC dev worlds in minutes, without scanning rooms: for each world,
# `objscan db eval` recognises the world's own models (scanned from 1 and 3 views) against the
# database of the other worlds' models that a model-disjoint bench built.
#
#   scripts/oasc_recognition_loo.sh BENCH_OUT OUT [--set key=value ...]
#
# BENCH_OUT: the output folder of `objscan bench --suite oasc-dev --db-from-worlds` (its db/worlds/*.db
# are the model-disjoint databases; a bench killed after its databases were built is enough).
# OUT: one JSON per world (resumable) and a summary on stdout: top-1 and top-5 category accuracy over
# the queries whose category is not `other`, the share predicted `other`, and the `other` queries.
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
python3 - "${out}" <<'EOF'
import glob, json, sys
queries = []
for f in sorted(glob.glob(sys.argv[1] + "/*.json")):
    queries += json.load(open(f))["queries"]
for views in (1, 3):
    q = [x for x in queries if x["views"] == views and x["truth"] != "other"]
    o = [x for x in queries if x["views"] == views and x["truth"] == "other"]
    if not q:
        continue
    top1 = sum(x["truth"] == x["predicted"] for x in q) / len(q)
    top5 = sum(x["top5"] for x in q) / len(q)
    pred_other = sum(x["predicted"] == "other" for x in q) / len(q)
    other_ok = sum(x["predicted"] == "other" for x in o) / max(1, len(o))
    line = (f"views {views}: {len(q)} queries, top-1 {top1:.3f}, top-5 {top5:.3f}, predicted other {pred_other:.3f}; "
            f"{len(o)} other queries, predicted other {other_ok:.3f}")
    if all("classifier" in x for x in q):  # recognition.classifier_weight > 0: the classifier's own first choice
        line += f"; classifier alone top-1 {sum(x['truth'] == x['classifier'] for x in q) / len(q):.3f}"
    print(line)
EOF
