#!/usr/bin/env python3
"""A short `objscan run`'s PLY files, read by Open3D's own reader (the peer build: python3-open3d,
installed by OBJSCAN_WITH_PEERS=1 scripts/install_deps.sh): the points come out coloured by category,
with as many points as the header announces, and each colour is one the header names for a category;
the header carries the `label` and `instance` fields. Without Open3D the test is skipped (exit 77),
reported by ctest as skipped, never as passed.

Environment (set by ctest): OBJSCAN_BINARY, OBJSCAN_TEST_DB (a small database).
By hand, on a run folder already written (e.g. the default run's):
    python3 tests/peers/test_open3d_reads_ply.py objscan-out/
"""
import os
import subprocess
import sys
import tempfile


def skip(why):
    print(f"SKIPPED: {why}")
    return 77


def header(path):
    lines = []
    with open(path, "rb") as f:
        for raw in f:
            line = raw.decode("ascii", "replace").rstrip("\r\n")
            lines.append(line)
            if line == "end_header":
                return lines
    raise AssertionError(f"{path}: no end_header")


def category_colours(lines):
    colours = {}
    for line in lines:
        parts = line.split()
        if len(parts) == 7 and parts[:2] == ["comment", "category"]:
            colours[(int(parts[4]), int(parts[5]), int(parts[6]))] = parts[3]
    return colours


def check(path, kind, o3d, np):
    lines = header(path)
    vertex_count = next(int(l.split()[2]) for l in lines if l.startswith("element vertex "))
    properties = [l.split()[-1] for l in lines if l.startswith("property ")]
    for field in ("red", "green", "blue", "label", "instance"):
        assert field in properties, f"{path}: no '{field}' property in {properties}"
    named = category_colours(lines)
    assert len(named) >= 2, f"{path}: the header names {len(named)} category colours"
    if kind == "points":
        geometry = o3d.io.read_point_cloud(path)
        points, colours = np.asarray(geometry.points), np.asarray(geometry.colors)
    else:
        geometry = o3d.io.read_triangle_mesh(path)
        points, colours = np.asarray(geometry.vertices), np.asarray(geometry.vertex_colors)
    assert len(points) == vertex_count, f"{path}: Open3D read {len(points)} of {vertex_count} vertices"
    assert len(colours) == len(points), f"{path}: Open3D found no colours ({len(colours)} for {len(points)} points)"
    rgb = {tuple(int(round(c * 255)) for c in row) for row in colours}
    unknown = rgb - set(named)
    assert not unknown, f"{path}: colours not named in the header: {sorted(unknown)[:5]}"
    labelled = {named[c] for c in rgb} - {"unrecognized", "structure", "background"}
    print(f"{os.path.basename(path)}: Open3D read {len(points)} points in {len(rgb)} colours "
          f"({', '.join(sorted(named[c] for c in rgb))})")
    return labelled


def main():
    try:
        import numpy as np
        import open3d as o3d
    except ImportError as e:
        return skip(f"Open3D's Python module is not installed ({e}): OBJSCAN_WITH_PEERS=1 scripts/install_deps.sh")
    if len(sys.argv) > 1:
        out = sys.argv[1]
    else:
        objscan, db = os.environ["OBJSCAN_BINARY"], os.environ["OBJSCAN_TEST_DB"]
        out = tempfile.mkdtemp(prefix="objscan_open3d_")
        r = subprocess.run([objscan, "run", "--scene", "procedural:bedroom:1", "--db", db, "--out", out, "--quiet",
                            "--set", "scanner.max_steps=25"], capture_output=True, text=True, timeout=1200)
        assert r.returncode == 0, f"objscan run: status {r.returncode}\n{r.stderr}"
    labelled = check(os.path.join(out, "scene.ply"), "points", o3d, np)
    labelled |= check(os.path.join(out, "models.ply"), "mesh", o3d, np)
    assert labelled, "no point carries the colour of a recognized category"
    print("Open3D reads scene.ply and models.ply with their category colours")
    return 0


if __name__ == "__main__":
    sys.exit(main())
