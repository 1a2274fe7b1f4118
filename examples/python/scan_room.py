#!/usr/bin/env python3
"""Scan a small procedural room with objscan from Python, step by step, and keep what it found.

    PYTHONPATH=build/python python3 examples/python/scan_room.py [--scene SPEC] [--db F.db]
                                                               [--seed N] [--max-steps N] [--out DIR]

With no --db it uses the built-in procedural database (built once, a few minutes, and cached like
`objscan run` does). It prints a line per step, then the run's metrics as one JSON line, and writes
the output folder of `objscan run` to --out plus points.npz (the reconstructed points with their
category labels and object ids).
"""
import argparse
import json
import os
import sys

import numpy as np

import objscan


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--scene", default="procedural:bedroom:1", help="scene SPEC (as objscan run --scene)")
    parser.add_argument("--db", default=None, help="model database file (default: the built-in one)")
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--max-steps", type=int, default=None, help="stop after this many steps")
    parser.add_argument("--set", action="append", default=[], dest="sets", help="config key=value (repeatable)")
    parser.add_argument("--out", default="objscan-py-out", help="output folder")
    args = parser.parse_args()

    sets = list(args.sets)
    if args.max_steps is not None:
        sets.append(f"scanner.max_steps={args.max_steps}")
    try:
        scan = objscan.Scan(args.scene, database=args.db, seed=args.seed, sets=sets)
    except (ValueError, FileNotFoundError) as e:
        sys.exit(f"scan_room.py: {e}")

    # Step the loop, looking at the map between steps.
    while scan.step():
        step = scan.last_step()
        objects = len(set(scan.analysis_instances().tolist()) - {-1})
        print(f"step {scan.steps:3d} {step['action']:8s} views {scan.views:3d}  points {scan.points().shape[0]:6d}  "
              f"objects in view {objects}", file=sys.stderr)
    scan.finish()

    record = scan.record()
    names = objscan.category_names()
    labels = scan.labels()
    found = sorted({o["category"] for o in record["objects"] if o["category"]})
    scan.save(args.out)
    np.savez_compressed(os.path.join(args.out, "points.npz"), xyz=scan.points(), label=labels,
                        object=scan.instances(), category_names=np.array(names))
    m = scan.metrics or {}
    print(json.dumps({"out": args.out, "terminated": scan.terminated, "views": scan.views,
                      "travel_m": round(scan.travel_m, 3), "objects": len(record["objects"]), "categories": found,
                      "recall": m.get("recall"), "precision": m.get("precision"),
                      "coverage_rate": m.get("coverage_rate")}))


if __name__ == "__main__":
    main()
