#!/usr/bin/env python3
"""Compares two run.json files apart from timings and resources (peak_rss_mb, cpu_s), the effective config and the per-object
provenance of the report rules (label_changes, and the per-rule fields run.json had before it), e.g.
to check that a change without behaviour change leaves runs as they were.

Usage: scripts/compare_runs.py OLD/run.json NEW/run.json   (prints the differences; exit 1 if any)"""
import json, sys
PROV = {"graph_cut_category", "size_rejected_category", "small_rejected_category",
        "wall_opening_replaced_category", "completion_rejected_model", "label_changes"}
def clean(j):
    j.pop("timing_s", None); j.pop("config", None); j.pop("peak_rss_mb", None); j.pop("cpu_s", None)
    for s in j.get("steps", []): s.pop("timing_ms", None)
    for o in j.get("objects", []):
        for k in PROV: o.pop(k, None)
    return j
def walk(a, b, path, out):
    if type(a) != type(b): out.append(f"{path}: {a!r} != {b!r}"); return
    if isinstance(a, dict):
        for k in sorted(set(a) | set(b)):
            if k not in a or k not in b: out.append(f"{path}.{k}: only in {'new' if k in b else 'old'}"); continue
            walk(a[k], b[k], f"{path}.{k}", out)
    elif isinstance(a, list):
        if len(a) != len(b): out.append(f"{path}: length {len(a)} != {len(b)}"); return
        for i, (x, y) in enumerate(zip(a, b)): walk(x, y, f"{path}[{i}]", out)
    elif a != b: out.append(f"{path}: {a!r} != {b!r}")
a = clean(json.load(open(sys.argv[1]))); b = clean(json.load(open(sys.argv[2])))
out = []; walk(a, b, "", out)
for line in out[:40]: print(line)
print(f"{len(out)} differences"); sys.exit(1 if out else 0)
