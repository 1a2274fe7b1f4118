#!/usr/bin/env python3
"""Compares two run.json files apart from timings and resources (peak_rss_mb, cpu_s), the effective config and the per-object
provenance of the report rules (label_changes, and the per-rule fields run.json had before it), e.g.
to check that a change without behaviour change leaves runs as they were.

With --exact, two run folders (OUT/ of `objscan run`) must be the same step for step: run.json
apart only from what is measured (compute time per stage and wall time; navigate_sim, the simulated
robot's driving time, is kept; peak_rss_mb, cpu_s), and every other file of the folders byte for byte.

Usage: scripts/compare_runs.py OLD/run.json NEW/run.json   (prints the differences; exit 1 if any)
       scripts/compare_runs.py --exact OLD_DIR NEW_DIR"""
import hashlib, json, os, sys
PROV = {"graph_cut_category", "size_rejected_category", "small_rejected_category",
        "wall_opening_replaced_category", "completion_rejected_model", "label_changes"}
def clean(j):
    j.pop("timing_s", None); j.pop("config", None); j.pop("peak_rss_mb", None); j.pop("cpu_s", None)
    for s in j.get("steps", []): s.pop("timing_ms", None)
    for o in j.get("objects", []):
        for k in PROV: o.pop(k, None)
    return j
def clean_measured(j):
    j.pop("peak_rss_mb", None); j.pop("cpu_s", None)
    j["timing_s"] = {"navigate_sim": j.get("timing_s", {}).get("navigate_sim")}
    for s in j.get("steps", []): s["timing_ms"] = {"navigate_sim": s.get("timing_ms", {}).get("navigate_sim")}
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
def digest(path):
    with open(path, "rb") as f: return hashlib.sha256(f.read()).hexdigest()
out = []
if sys.argv[1] == "--exact":
    old, new = sys.argv[2], sys.argv[3]
    a = clean_measured(json.load(open(os.path.join(old, "run.json"))))
    b = clean_measured(json.load(open(os.path.join(new, "run.json"))))
    walk(a, b, "", out)
    names = sorted(n for n in set(os.listdir(old)) | set(os.listdir(new)) if n != "run.json")
    for n in names:
        p, q = os.path.join(old, n), os.path.join(new, n)
        if not (os.path.isfile(p) and os.path.isfile(q)):
            out.append(f"{n}: only in {'new' if os.path.exists(q) else 'old'}")
        elif digest(p) != digest(q): out.append(f"{n}: differs")
    steps, objects = len(a.get("steps", [])), len(a.get("objects", []))
    print(f"run.json ({steps} steps, {objects} objects) and {len(names)} files compared")
else:
    a = clean(json.load(open(sys.argv[1]))); b = clean(json.load(open(sys.argv[2])))
    walk(a, b, "", out)
for line in out[:40]: print(line)
print(f"{len(out)} differences"); sys.exit(1 if out else 0)
