#!/usr/bin/env python3
"""scripts/step_costs.py on run.json files whose step timings are known."""
import csv
import json
import os
import subprocess
import sys
import tempfile

SCRIPT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "scripts", "step_costs.py")


def write_run(folder, scene, recognize_ms):
    os.makedirs(folder, exist_ok=True)
    steps = []
    for i, r in enumerate(recognize_ms):
        timing = {"sense": 1.0, "fuse": 2.0, "segment": 3.0, "recognize": r, "nbo": 0.0, "nbv": 4.0,
                  "navigate_sim": 1000.0}
        timing["wall"] = sum(v for k, v in timing.items() if k != "navigate_sim") + 5.0  # 5 ms elsewhere
        steps.append({"index": i, "action": "nbo", "components": 10 + i, "objects": 3, "timing_ms": timing})
    with open(os.path.join(folder, "run.json"), "w") as f:
        json.dump({"scene": scene, "cpu_s": 12.5, "steps": steps}, f)


def main():
    failures = []

    def check(cond, what):
        if not cond:
            failures.append(what)

    with tempfile.TemporaryDirectory() as tmp:
        # Ten steps: recognize 10, 20, ..., 100 ms. First fifth (2 steps) mean 15, last fifth 95.
        write_run(os.path.join(tmp, "runs", "a"), "procedural:bedroom:1", [10.0 * (i + 1) for i in range(10)])
        write_run(os.path.join(tmp, "runs", "b"), "procedural:kitchen:2", [50.0] * 5)
        out_csv = os.path.join(tmp, "steps.csv")
        svg_dir = os.path.join(tmp, "svg")
        p = subprocess.run([sys.executable, SCRIPT, os.path.join(tmp, "runs"), "--csv", out_csv, "--svg-dir", svg_dir],
                           capture_output=True, text=True)
        check(p.returncode == 0, f"exit {p.returncode}: {p.stderr}")
        rows = [line for line in p.stdout.splitlines() if line.startswith("| procedural")]
        check(len(rows) == 2, f"two table rows, got {rows}")
        bedroom = next((r for r in rows if "bedroom" in r), "")
        cells = [c.strip() for c in bedroom.strip("|").split("|")]
        # run, steps, cpu_s, sense, fuse, segment, recognize, nbo, nbv, wall, ratio
        check(cells[1] == "10" and cells[2] == "12.5", f"steps and cpu_s: {cells}")
        check(cells[6] == "15 / 95", f"recognize first/last fifth: {cells[6]}")
        # wall = 1 + 2 + 3 + r + 0 + 4 + 5 = r + 15: first 30, last 110, ratio 3.67.
        check(cells[9] == "30 / 110", f"wall first/last fifth: {cells[9]}")
        check(cells[10] == "3.67", f"ratio: {cells[10]}")
        with open(out_csv) as f:
            table = list(csv.DictReader(f))
        check(len(table) == 15, f"15 CSV rows, got {len(table)}")
        check(all(float(r["other"]) == 5.0 for r in table), "other = wall - stages = 5 ms on every step")
        check(sorted(os.listdir(svg_dir)) == ["procedural_bedroom_1.svg", "procedural_kitchen_2.svg"],
              f"SVGs: {sorted(os.listdir(svg_dir))}")
        with open(os.path.join(svg_dir, "procedural_bedroom_1.svg")) as f:
            svg = f.read()
        check(svg.startswith("<svg") and svg.rstrip().endswith("</svg>"), "a whole SVG document")
        # A folder without runs: one line, non-zero exit.
        p = subprocess.run([sys.executable, SCRIPT, os.path.join(tmp, "svg")], capture_output=True, text=True)
        check(p.returncode != 0 and "no run.json found" in p.stderr and p.stderr.count("\n") == 1,
              f"no runs: exit {p.returncode}, {p.stderr!r}")
    if failures:
        for f in failures:
            print("FAIL:", f)
        return 1
    print("step_costs.py: all checks passed")
    return 0


if __name__ == "__main__":
    sys.exit(main())
