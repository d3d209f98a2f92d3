#!/usr/bin/env python3
"""Benchmark: compute_feature_lines_and_patches against MeshLab's crease-edge selection.

Both run in this process on the same mesh (organic/armadillo.off subdivided twice with
Loop, about 830k triangles, by default). Prints a markdown table and writes it to
benchmarks/features.md. Goal (issue 2): our full feature + patch recovery within 1.5x
the time of MeshLab's crease selection alone.
"""
import argparse
import datetime
import pathlib
import platform
import time

import meshregrid  # noqa: F401
import pymeshlab

REPO = pathlib.Path(__file__).resolve().parents[1]
DATA = REPO.parent / "shared" / "data"


def best_of(repeats, call):
    times = []
    for _ in range(repeats):
        t = time.perf_counter()
        call()
        times.append(time.perf_counter() - t)
    return min(times)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--mesh", default=str(DATA / "organic" / "armadillo.off"))
    ap.add_argument("--subdivisions", type=int, default=2)
    ap.add_argument("--repeats", type=int, default=5)
    ap.add_argument("--angle", type=float, default=30.0)
    ap.add_argument("--out", default=str(REPO / "benchmarks" / "features.md"))
    args = ap.parse_args()

    ms = pymeshlab.MeshSet()
    ms.load_new_mesh(args.mesh)
    if args.subdivisions:
        ms.meshing_surface_subdivision_loop(iterations=args.subdivisions, threshold=pymeshlab.PercentageValue(0))
    faces = ms.current_mesh().face_number()

    crease = best_of(args.repeats, lambda: ms.compute_selection_crease_per_edge(
        angledegneg=-args.angle, angledegpos=args.angle))
    ours = best_of(args.repeats, lambda: ms.compute_feature_lines_and_patches(ridge_angle=args.angle))
    ours_no_colour = best_of(args.repeats, lambda: ms.compute_feature_lines_and_patches(
        ridge_angle=args.angle, color_patches=False))
    r = ms.compute_feature_lines_and_patches(ridge_angle=args.angle)

    rows = [
        "| filter | what it computes | time (s, best of %d) | ratio to MeshLab crease |" % args.repeats,
        "|---|---|---|---|",
        f"| MeshLab `compute_selection_crease_per_edge` | ridge edges only | {crease:.3f} | 1.00 |",
        f"| `compute_feature_lines_and_patches` | ridges, corners, lines, patches, patch_id, colours | {ours:.3f} | {ours / crease:.2f} |",
        f"| `compute_feature_lines_and_patches(color_patches=False)` | same without face colours | {ours_no_colour:.3f} | {ours_no_colour / crease:.2f} |",
    ]
    header = [
        "## Feature lines and patches (`scripts/bench_features.py`)",
        "",
        f"Command: `.venv/bin/python scripts/bench_features.py` — {datetime.date.today()}, "
        f"{platform.machine()} {platform.system()}, 2 cores (shared with other jobs while measured); input {pathlib.Path(args.mesh).name} "
        f"Loop-subdivided {args.subdivisions}x: {faces} triangles; ridge angle {args.angle} deg. "
        f"Result: {r['ridge_edges']} ridge edges, {r['corners']} corners, {r['lines']} lines, {r['patches']} patches.",
        "",
    ]
    text = "\n".join(header + rows) + "\n\nGoal: ratio <= 1.5.\n"
    print(text)
    pathlib.Path(args.out).write_text(text)
    import subprocess, sys
    subprocess.run([sys.executable, str(REPO / "scripts" / "collect_benchmarks.py")], check=True)


if __name__ == "__main__":
    main()
