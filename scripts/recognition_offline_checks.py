#!/usr/bin/env python3
"""Offline checks of recognition ideas on finished runs, without scanning again (numpy only).

  global-features BENCH_DIR...   Can global shape statistics of the reported objects (heights,
                                 footprint, height histograms of points and of upward faces) tell
                                 their ground-truth categories apart? Leave one world out over the
                                 runs of `objscan bench` folders (every method folder `ours`): the
                                 classifiers train on the other worlds' objects of every given bench
                                 (an optimistic bound: real segments of real rooms, not database
                                 scans) and are compared with the loop's own labels.
  category-votes LOO_DIR         Does naming the category by the scores of several retrieved models
                                 beat naming it by the best one? Reads the `db eval` JSON files of
                                 scripts/oasc_recognition_loo.sh run with the whole shortlist refined
                                 and listed (--set recognition.refine_entries=0
                                 --set recognition.max_per_category=0
                                 --set recognition.num_similar_models=20).

Results of both on OASC dev: docs/results/oasc-dev-2026-11-26-recognition-offline-checks.md.
"""
import argparse
import collections
import glob
import json
import math
import os
import sys

import numpy as np

PLY_TYPES = {"float": "<f4", "uchar": "u1", "int": "<i4"}


def read_scene_ply(path):
    """The vertex table of a run's scene.ply (binary little-endian, see docs/outputs.md)."""
    with open(path, "rb") as f:
        props, count = [], 0
        while True:
            line = f.readline().decode().strip()
            if line.startswith("element vertex"):
                count = int(line.split()[2])
            elif line.startswith("property"):
                kind, name = line.split()[1:3]
                props.append((name, PLY_TYPES[kind]))
            elif line == "end_header":
                break
        dtype = np.dtype(props)
        return np.frombuffer(f.read(count * dtype.itemsize), dtype=dtype, count=count)


def shape_features(points, normals):
    """29 numbers: top, bottom and height (m); footprint extents along the principal axes (m);
    log point count; shares of vertical, downward and upward faces; the points' and the upward faces'
    shares in ten 25 cm height bins from the floor."""
    z = points[:, 2]
    top, bottom = z.max(), np.percentile(z, 1)
    xy = points[:, :2] - points[:, :2].mean(0)
    _, axes = np.linalg.eigh(np.cov(xy.T))
    along = xy @ axes
    extents = np.sort(np.percentile(along, 98, axis=0) - np.percentile(along, 2, axis=0))
    bins = np.linspace(0.0, 2.5, 11)
    up = normals[:, 2] > 0.85
    points_by_height = np.histogram(np.clip(z, 0, 2.49), bins)[0] / len(z)
    up_by_height = np.histogram(np.clip(z[up], 0, 2.49), bins)[0] / len(z)
    return np.concatenate([[top, bottom, top - bottom, extents[1], extents[0], math.log(len(z)),
                            np.mean(np.abs(normals[:, 2]) < 0.3), np.mean(normals[:, 2] < -0.85), up.mean()],
                           points_by_height, up_by_height])


def objects_of_bench(bench_dir, min_points=50):
    rows = []
    for run_json in sorted(glob.glob(os.path.join(bench_dir, "runs", "*", "ours", "run.json"))):
        run = json.load(open(run_json))
        world = run_json.split(os.sep)[-3]
        truth = {i["instance"]: i["category"] for i in run["metrics"]["instances"]}
        v = read_scene_ply(os.path.join(os.path.dirname(run_json), "scene.ply"))
        points = np.stack([v["x"], v["y"], v["z"]], 1)
        normals = np.stack([v["nx"], v["ny"], v["nz"]], 1)
        order = np.argsort(v["object_id"], kind="stable")
        sorted_ids = v["object_id"][order]
        for o in run["objects"]:
            lo, hi = np.searchsorted(sorted_ids, o["id"]), np.searchsorted(sorted_ids, o["id"], "right")
            gt = truth.get(o.get("gt_instance")) if o.get("gt_instance") is not None else None
            if hi - lo < min_points or gt is None:
                continue
            idx = order[lo:hi]
            rows.append(dict(world=world, predicted=o.get("category"), truth=gt,
                             features=shape_features(points[idx], normals[idx])))
    return rows


def softmax_classifier(x, y, num_classes, l2=1e-2, iterations=400, step=0.5):
    a = np.hstack([x, np.ones((len(x), 1))])
    w = np.zeros((a.shape[1], num_classes))
    target = np.eye(num_classes)[y]
    for _ in range(iterations):
        z = a @ w
        p = np.exp(z - z.max(1, keepdims=True))
        p /= p.sum(1, keepdims=True)
        w -= step * (a.T @ (p - target) / len(a) + l2 * w)
    return lambda q: (np.hstack([q, np.ones((len(q), 1))]) @ w).argmax(1)


def global_features(bench_dirs):
    rows = [r for b in bench_dirs for r in objects_of_bench(b)]
    if not rows:
        sys.exit("global-features: no runs with objects under " + " ".join(bench_dirs))
    categories = sorted({r["truth"] for r in rows})
    index = {c: i for i, c in enumerate(categories)}
    x = np.array([r["features"] for r in rows])
    y = np.array([index[r["truth"]] for r in rows])
    count = collections.Counter()
    for world in sorted({r["world"] for r in rows}):
        test = np.array([r["world"] == world for r in rows])
        mean, scale = x[~test].mean(0), x[~test].std(0) + 1e-6
        train_x, test_x = (x[~test] - mean) / scale, (x[test] - mean) / scale
        distances = ((test_x[:, None, :] - train_x[None, :, :]) ** 2).sum(2)
        knn = [collections.Counter(y[~test][n]).most_common(1)[0][0] for n in np.argsort(distances, 1)[:, :7]]
        softmax = softmax_classifier(train_x, y[~test], len(categories))(test_x)
        for r, k, s in zip([r for r in rows if r["world"] == world], knn, softmax):
            count["objects"] += 1
            count["knn"] += categories[k] == r["truth"]
            count["softmax"] += categories[s] == r["truth"]
            if r["predicted"] in (None, "other"):
                continue  # not an output of precision
            count["labelled"] += 1
            count["loop right"] += r["predicted"] == r["truth"]
            count["knn right"] += categories[k] == r["truth"]
            count["softmax right"] += categories[s] == r["truth"]
            agree = categories[s] == r["predicted"]
            count["agree"] += agree
            count["agree right"] += agree and r["predicted"] == r["truth"]
    n = count["labelled"]
    print(f"{count['objects']} objects on a ground-truth object, {n} of them reported with a label")
    print(f"right category of the labelled ones: loop {count['loop right'] / n:.3f}, "
          f"7-NN {count['knn right'] / n:.3f}, softmax {count['softmax right'] / n:.3f}")
    print(f"loop and softmax agree on {count['agree']} of {n}; right when they agree: "
          f"{count['agree right'] / max(1, count['agree']):.3f}")
    print(f"all {count['objects']} objects: 7-NN {count['knn'] / count['objects']:.3f}, "
          f"softmax {count['softmax'] / count['objects']:.3f}")


def category_votes(loo_dir):
    queries = [q for f in sorted(glob.glob(os.path.join(loo_dir, "*.json")))
               for q in json.load(open(f))["queries"] if q["truth"] != "other"]
    if not queries:
        sys.exit("category-votes: no db eval queries under " + loo_dir)
    scores = {
        "fit x O_visible (default rank)": lambda e: e["fit"] * e["visible_objectness"],
        "fit x O": lambda e: e["fit"] * e["objectness"],
        "fit x O_visible x O": lambda e: e["fit"] * e["visible_objectness"] * e["objectness"],
    }

    def best_model(by_category, ranked):
        return ranked[0]["category"]

    def mean_of_two(by_category, ranked):
        return max(by_category, key=lambda c: sum(by_category[c][:2]) / 2)

    def sum_of_three(by_category, ranked):
        return max(by_category, key=lambda c: sum(by_category[c][:3]))

    def soft_vote(temperature):
        return lambda by_category, ranked: max(
            by_category, key=lambda c: sum(math.exp(temperature * (s - by_category[ranked[0]["category"]][0]))
                                           for s in by_category[c]))

    def rank_vote(by_category, ranked):
        votes = collections.Counter()
        for i, e in enumerate(ranked[:5]):
            votes[e["category"]] += 1.0 / (i + 1)
        return votes.most_common(1)[0][0]

    rules = {"best model": best_model, "mean of the best two": mean_of_two, "sum of the best three": sum_of_three,
             "soft vote, t = 50": soft_vote(50.0), "soft vote, t = 100": soft_vote(100.0),
             "rank vote of the best five": rank_vote}
    print("| score | category by | top-1, 1 view | top-1, 3 views |")
    print("|---|---|---|---|")
    for score_name, score in scores.items():
        for rule_name, rule in rules.items():
            cells = []
            for views in (1, 3):
                qs = [q for q in queries if q["views"] == views]
                right = 0
                for q in qs:
                    ranked = sorted(q["retrieved"], key=lambda e: -score(e))
                    by_category = collections.defaultdict(list)
                    for e in ranked:
                        by_category[e["category"]].append(score(e))
                    right += rule(by_category, ranked) == q["truth"]
                cells.append(f"{right / len(qs):.1%} ({len(qs)})" if qs else "-")
            print(f"| {score_name} | {rule_name} | {cells[0]} | {cells[1]} |")


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = parser.add_subparsers(dest="check", required=True)
    g = sub.add_parser("global-features", help="leave-one-world-out classifiers on global shape statistics")
    g.add_argument("bench_dirs", nargs="+")
    c = sub.add_parser("category-votes", help="category by several retrieved models' scores")
    c.add_argument("loo_dir")
    args = parser.parse_args()
    if args.check == "global-features":
        global_features(args.bench_dirs)
    else:
        category_votes(args.loo_dir)


if __name__ == "__main__":
    main()
