#!/usr/bin/env python3
"""Benchmark: interpolatory quad subdivision against MeshLab's Catmull-Clark, same run.

Both filters refine the same quad meshes to the same number of output faces (4^k times the
input quads). Prints a markdown table and writes benchmarks/quadsub.md.
"""
import argparse
import datetime
import pathlib
import platform
import time

import meshregrid  # noqa: F401
import pymeshlab

REPO = pathlib.Path(__file__).resolve().parents[1]
DATA = REPO.parent / "shared" / "data" / "quad"


def best_of(repeats, make, run):
    best, out = float("inf"), None
    for _ in range(repeats):
        ms = make()
        t = time.perf_counter()
        run(ms)
        best = min(best, time.perf_counter() - t)
        out = ms.current_mesh().face_number()
    return best, out


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--iterations", type=int, default=4, help="our steps; even (MeshLab's filter does two per call)")
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--out", default=str(REPO / "benchmarks" / "quadsub.md"))
    args = ap.parse_args()
    rows = ["| mesh | input quads | output triangles | interpolatory quad (s) | MeshLab Catmull-Clark (s) | ratio (ours / CC) |",
            "|---|---|---|---|---|---|"]
    for name in ("quadknot.obj", "spot_quadrangulated.obj"):
        def make():
            ms = pymeshlab.MeshSet()
            ms.load_new_mesh(str(DATA / name))
            return ms
        first = make()  # keep the MeshSet alive while its mesh is read
        quads = len(first.current_mesh().polygonal_face_list())
        ours, ours_faces = best_of(args.repeats, make, lambda ms: ms.meshing_surface_subdivision_interpolatory_quad(
            iterations=args.iterations))
        cc, cc_faces = best_of(args.repeats, make, lambda ms: [ms.meshing_surface_subdivision_catmull_clark()
                                                              for _ in range(args.iterations // 2)])
        assert ours_faces == cc_faces, (ours_faces, cc_faces)
        rows.append(f"| {name} | {quads} | {ours_faces} | {ours:.3f} | {cc:.3f} | {ours / cc:.2f} |")
    text = "\n".join([
        "## Interpolatory quad subdivision (`scripts/bench_quadsub.py`)", "",
        f"Command: `.venv/bin/python scripts/bench_quadsub.py` — {datetime.date.today()}, {platform.machine()} "
        f"{platform.system()}, 2 cores; {args.iterations} steps each, best of {args.repeats}; MeshLab's filter is "
        "applied once per two steps (each call multiplies the quads by 16). Goal: ratio <= 1.", ""] + rows) + "\n"
    print(text)
    pathlib.Path(args.out).write_text(text)


if __name__ == "__main__":
    main()
