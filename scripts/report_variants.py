#!/usr/bin/env python3
"""Tabulates report_variants.json over the runs of a bench folder (objscan bench ... --set
eval.report_variants=ablation|FILE.yaml): per variant, the mean over runs of recall, precision and
coverage rate, and the pooled true positives / outputs / ground truth.

Usage: scripts/report_variants.py BENCH_DIR [--method ours]
"""
import glob
import json
import os
import sys


def main():
    args = sys.argv[1:]
    if not args or args[0] in ("-h", "--help"):
        print(__doc__)
        return 0 if args else 2
    root = args[0]
    method = args[args.index("--method") + 1] if "--method" in args else "ours"
    files = sorted(glob.glob(os.path.join(root, "runs", "*", method, "report_variants.json")))
    if not files:
        print(f"report_variants.py: no runs/*/{method}/report_variants.json under {root}", file=sys.stderr)
        return 2
    table = {}
    order = []
    for path in files:
        with open(path) as f:
            data = json.load(f)
        for name, v in data.items():
            if name not in table:
                table[name] = []
                order.append(name)
            table[name].append(v)
    print(f"{len(files)} runs of {method} in {root}\n")
    print("| variant | runs | recall | precision | coverage | TP / outputs / GT |")
    print("|---|---|---|---|---|---|")
    for name in order:
        rows = table[name]
        n = len(rows)
        mean = lambda k: 100.0 * sum(r[k] for r in rows) / n
        tp = sum(r["true_positives"] for r in rows)
        outs = sum(r["output_objects"] for r in rows)
        gt = sum(r["ground_truth_objects"] for r in rows)
        print(f"| {name} | {n} | {mean('recall'):.1f} | {mean('precision'):.1f} | {mean('coverage_rate'):.1f} "
              f"| {tp} / {outs} / {gt} |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
