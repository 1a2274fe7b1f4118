#!/usr/bin/env python3
"""Per-step cost of objscan runs: how each stage's time grows over a run.

Reads run.json files (or folders holding them, searched recursively) and writes
  - a CSV with one row per step: run, step, explored area so far is not recorded per step, so the
    map's size is given by the number of segments (components) and objects the step saw,
    then the time of each stage in ms (sense, fuse, segment, recognize, nbo, nbv, wall);
  - an SVG per run (stacked stage times per step, with the component count drawn over them);
  - on stdout, a table per run: mean ms per step of each stage over the first and the last fifth of
    the steps, and their ratio (the issue's "per-step CPU at the end no more than 2x the start").

Wall time per stage is what run.json records (timing_ms); the robot's simulated driving
(navigate_sim) is not compute and is left out.

  scripts/step_costs.py RUN_OR_FOLDER... --csv steps.csv --svg-dir plots/
"""
import argparse
import csv
import json
import os
import sys

STAGES = ["sense", "fuse", "segment", "recognize", "nbo", "nbv"]
COLOURS = {"sense": "#4e79a7", "fuse": "#f28e2b", "segment": "#59a14f", "recognize": "#e15759",
           "nbo": "#b07aa1", "nbv": "#76b7b2", "other": "#bab0ab"}


def find_runs(paths):
    """(run.json path, its folder relative to the argument that named it) pairs."""
    runs = []
    for p in paths:
        if os.path.isfile(p):
            runs.append((p, os.path.basename(os.path.dirname(os.path.abspath(p)))))
            continue
        if not os.path.isdir(p):
            sys.exit(f"step_costs.py: error: {p}: no such file or folder")
        for root, _dirs, files in os.walk(p):
            if "run.json" in files:
                rel = os.path.relpath(root, p)
                runs.append((os.path.join(root, "run.json"), os.path.basename(os.path.abspath(p)) if rel == "." else rel))
    if not runs:
        sys.exit("step_costs.py: error: no run.json found below " + " ".join(paths))
    return sorted(runs)


def load_steps(path, folder_name):
    try:
        with open(path) as f:
            run = json.load(f)
    except (OSError, json.JSONDecodeError) as e:
        sys.exit(f"step_costs.py: error: {path}: {e}")
    steps = []
    for s in run.get("steps", []):
        t = s.get("timing_ms", {})
        row = {"step": s.get("index", len(steps)), "action": s.get("action", ""),
               "components": s.get("components", 0), "objects": s.get("objects", 0)}
        for stage in STAGES:
            row[stage] = float(t.get(stage, 0.0))
        wall = float(t.get("wall", sum(row[st] for st in STAGES)))
        row["wall"] = wall
        row["other"] = max(0.0, wall - sum(row[st] for st in STAGES))
        steps.append(row)
    # A scene spec names the run unless it is a file path (a world): then the run's folder does
    # (a bench's runs/<scene>/<method>).
    name = run.get("scene", "")
    if isinstance(name, dict):
        name = name.get("spec") or name.get("name") or ""
    name = str(name)
    if not name or "/" in name:
        name = folder_name
    return name, run, steps


def fifth_means(steps, key):
    n = len(steps)
    k = max(1, n // 5)
    first = sum(s[key] for s in steps[:k]) / k
    last = sum(s[key] for s in steps[-k:]) / k
    return first, last


def write_svg(path, name, steps):
    width, height, left, bottom, top, right = 900, 400, 60, 40, 52, 60
    plot_w, plot_h = width - left - right, height - top - bottom
    n = max(1, len(steps))
    max_wall = max([s["wall"] for s in steps] + [1.0])
    max_comp = max([s["components"] for s in steps] + [1])
    bar = plot_w / n
    out = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{width}" height="{height}" '
           f'font-family="sans-serif" font-size="11">',
           f'<rect width="{width}" height="{height}" fill="white"/>',
           f'<text x="{left}" y="18" font-size="12">{name}: ms per step by stage; segments (line)</text>']
    for i, s in enumerate(steps):
        y = top + plot_h
        for stage in STAGES + ["other"]:
            h = plot_h * s[stage] / max_wall
            if h <= 0:
                continue
            y -= h
            out.append(f'<rect x="{left + i * bar:.2f}" y="{y:.2f}" width="{max(bar, 0.5):.2f}" '
                       f'height="{h:.2f}" fill="{COLOURS[stage]}"/>')
    points = " ".join(f'{left + (i + 0.5) * bar:.1f},{top + plot_h * (1 - s["components"] / max_comp):.1f}'
                      for i, s in enumerate(steps))
    out.append(f'<polyline points="{points}" fill="none" stroke="black" stroke-width="1.2"/>')
    out.append(f'<line x1="{left}" y1="{top + plot_h}" x2="{left + plot_w}" y2="{top + plot_h}" stroke="black"/>')
    out.append(f'<line x1="{left}" y1="{top}" x2="{left}" y2="{top + plot_h}" stroke="black"/>')
    for frac in (0.0, 0.5, 1.0):
        y = top + plot_h * (1 - frac)
        out.append(f'<text x="{left - 6}" y="{y + 4:.1f}" text-anchor="end">{max_wall * frac:.0f}</text>')
        out.append(f'<text x="{left + plot_w + 6}" y="{y + 4:.1f}">{max_comp * frac:.0f}</text>')
    out.append(f'<text x="{left + plot_w / 2}" y="{height - 8}" text-anchor="middle">step (of {len(steps)})</text>')
    out.append(f'<text x="{left - 30}" y="{top - 4}" text-anchor="end">ms</text>')
    out.append(f'<text x="{left + plot_w + 6}" y="{top - 4}">segments</text>')
    x = left
    for stage in STAGES + ["other"]:
        out.append(f'<rect x="{x}" y="26" width="10" height="10" fill="{COLOURS[stage]}"/>')
        out.append(f'<text x="{x + 13}" y="35">{stage}</text>')
        x += 80
    out.append("</svg>")
    tmp = path + ".tmp"
    with open(tmp, "w") as f:
        f.write("\n".join(out) + "\n")
    os.replace(tmp, path)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("paths", nargs="+", help="run.json files or folders holding them")
    ap.add_argument("--csv", help="write one row per step here")
    ap.add_argument("--svg-dir", help="write one SVG per run into this folder")
    args = ap.parse_args()
    rows = []
    print("| run | steps | cpu_s | " + " | ".join(f"{st} first/last ms" for st in STAGES + ["wall"]) +
          " | wall last/first |")
    print("|---|---|---|" + "---|" * (len(STAGES) + 2))
    for path, folder_name in find_runs(args.paths):
        name, run, steps = load_steps(path, folder_name)
        if not steps:
            print(f"step_costs.py: warning: {path}: no steps", file=sys.stderr)
            continue
        cells = []
        for stage in STAGES + ["wall"]:
            first, last = fifth_means(steps, stage)
            cells.append(f"{first:.0f} / {last:.0f}")
        first, last = fifth_means(steps, "wall")
        ratio = last / first if first > 0 else float("nan")
        print(f"| {name} | {len(steps)} | {run.get('cpu_s', '')} | " + " | ".join(cells) + f" | {ratio:.2f} |")
        for s in steps:
            rows.append(dict(run=name, **s))
        if args.svg_dir:
            os.makedirs(args.svg_dir, exist_ok=True)
            safe = "".join(c if c.isalnum() or c in "-_." else "_" for c in name)
            write_svg(os.path.join(args.svg_dir, safe + ".svg"), name, steps)
    if args.csv and rows:
        fields = ["run", "step", "action", "components", "objects"] + STAGES + ["other", "wall"]
        tmp = args.csv + ".tmp"
        with open(tmp, "w", newline="") as f:
            w = csv.DictWriter(f, fieldnames=fields)
            w.writeheader()
            for r in rows:
                w.writerow({k: r[k] for k in fields})
        os.replace(tmp, args.csv)


if __name__ == "__main__":
    main()
