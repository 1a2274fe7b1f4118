#!/usr/bin/env python3
"""Summary of `objscan db eval` outputs (one or more JSON files, e.g. one per held-out world).

    scripts/recognition_summary.py EVAL.json... [--json OUT.json] [--sweep]

For each kind of query (whole objects from 1 and from 3 views, pieces = half a view) over the
queries whose category is not `other`: top-1 of the name given (recognition.naming), of the best
retrieved model alone (the paper) and of the category classifier alone; top-1 per category and the
confusion of the name. Over the queries whose category is `other` (props, plants: what the loop
should report as not recognized): the share named `other`. --sweep re-decides the name offline
from each query's posterior and M(c) for other naming weights (recognition.naming.classifier_weight,
absent_share, other_weight), without scanning.
"""
import argparse
import collections
import json
import sys


def kind(q):
    return "piece" if q.get("piece") else f"{q['views']} view" + ("s" if q["views"] > 1 else "")


def name(q, weight, absent, other_weight):
    post = dict(q.get("posterior", {}))
    if "other" in post:
        post["other"] *= other_weight
    fit = {}
    for r in q["retrieved"]:
        fit[r["category"]] = max(fit.get(r["category"], 0.0), max(0.0, r["rank_score"]))
    weakest = min(fit.values()) if fit else 0.0
    best, best_score = None, -1.0
    cats = set(post) | set(fit)
    for c in sorted(cats):
        if c in ("floor", "wall", "ceiling"):
            continue
        p = post.get(c, 0.0) ** weight if post else 1.0
        f = fit.get(c, absent * weakest) if fit else 1.0
        if (post and post.get(c, 0.0) <= 0.0 and c not in fit) or (not post and c not in fit):
            continue
        if p * f > best_score:
            best, best_score = c, p * f
    return best


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("files", nargs="+")
    ap.add_argument("--json", help="write the summary as JSON here")
    ap.add_argument("--sweep", action="store_true", help="re-decide names for other naming weights")
    a = ap.parse_args()
    queries = []
    run_naming = None
    for f in a.files:
        j = json.load(open(f))
        queries += j["queries"]
        # Outputs written before the naming options were recorded were named with other_weight 0.5.
        naming = j.get("naming", {"classifier_weight": 1.0, "absent_share": 0.5, "other_weight": 0.5})
        if run_naming not in (None, naming):
            sys.exit(f"recognition_summary.py: {f} was named with other naming options than the first file")
        run_naming = naming
    if not queries:
        sys.exit("recognition_summary.py: no queries")
    out = {}
    kinds = ["1 view", "3 views", "piece"]
    for k in kinds:
        q = [x for x in queries if kind(x) == k and x["truth"] != "other"]
        bg = [x for x in queries if kind(x) == k and x["truth"] == "other"]
        if not q:
            continue
        n = len(q)
        named = sum(x["truth"] == x["predicted"] for x in q) / n
        retrieval = sum(x["truth"] == x.get("retrieval", x["predicted"]) for x in q) / n
        classifier = sum(x["truth"] == x.get("classifier") for x in q) / n
        per_cat = collections.defaultdict(lambda: [0, 0])
        confusion = collections.defaultdict(collections.Counter)
        for x in q:
            per_cat[x["truth"]][0] += x["truth"] == x["predicted"]
            per_cat[x["truth"]][1] += 1
            confusion[x["truth"]][x["predicted"]] += 1
        other_named_other = sum(x["predicted"] == "other" for x in bg) / len(bg) if bg else None
        out[k] = {"queries": n, "named_top1": named, "retrieval_top1": retrieval, "classifier_top1": classifier,
                  "other_queries": len(bg), "other_named_other": other_named_other,
                  "per_category": {c: {"top1": r / t, "queries": t} for c, (r, t) in sorted(per_cat.items())},
                  "confusion": {c: dict(v) for c, v in sorted(confusion.items())}}
        print(f"{k:8s}: {n:4d} queries, named {named:.3f}, best model alone {retrieval:.3f}, classifier alone {classifier:.3f}")
        if bg:
            print(f"          other queries: {len(bg)}, named other {other_named_other:.3f}")
        print("          per category: " + ", ".join(f"{c} {r}/{t}" for c, (r, t) in sorted(per_cat.items())))
        if a.sweep:
            line = []
            for w in (0.0, 0.5, 1.0, 2.0, 4.0, 100.0):
                for absent in (0.0, 0.5, 1.0):
                    acc = sum(x["truth"] == name(x, w, absent, run_naming["other_weight"]) for x in q) / n
                    line.append(f"w{w:g}/a{absent:g} {acc:.3f}")
            print("          sweep: " + ", ".join(line))
            line = []
            for ow in (0.25, 0.5, 0.75, 1.0, 1.5, 2.0, 3.0):
                acc = sum(x["truth"] == name(x, run_naming["classifier_weight"], run_naming["absent_share"], ow)
                          for x in q) / n
                spec = (sum(name(x, run_naming["classifier_weight"], run_naming["absent_share"], ow) == "other"
                            for x in bg) / len(bg)) if bg else float("nan")
                line.append(f"other_weight {ow:g}: {acc:.3f} (other named other {spec:.3f})")
            print("          sweep: " + ", ".join(line))
    if a.json:
        json.dump(out, open(a.json, "w"), indent=2)


if __name__ == "__main__":
    main()
