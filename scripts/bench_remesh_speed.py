#!/usr/bin/env python3
"""Benchmark: output triangles per second of our advancing-front remesher against MeshLab's
isotropic remesher (default iterations), in the same run, on a large input.

The input is organic/armadillo.off subdivided twice with PyMeshLab's Loop subdivision
(threshold 0: every edge splits), about 830k triangles, as ../shared/data/README.md suggests.
Both filters get the same absolute target length and feature angle. Writes
benchmarks/remesh_speed.md. Goal (issue #3): ours / MeshLab triangles per second >= 1.
"""
import argparse
import datetime
import pathlib
import platform
import time

import meshregrid  # noqa: F401  (loads the plugins)
import pymeshlab

REPO = pathlib.Path(__file__).resolve().parents[1]
DATA = REPO.parent / "shared" / "data"


def large_input() -> pymeshlab.MeshSet:
    ms = pymeshlab.MeshSet()
    ms.load_new_mesh(str(DATA / "organic" / "armadillo.off"))
    ms.meshing_surface_subdivision_loop(iterations=2, threshold=pymeshlab.PureValue(0))
    return ms


def timed(run) -> tuple:
    """Seconds, output faces and the filter's dictionary of one run on a fresh copy of the input."""
    ms = large_input()
    t = time.perf_counter()
    result = run(ms)
    return time.perf_counter() - t, ms.current_mesh().face_number(), result


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--percents", default="1,0.5", help="target lengths in %% of the diagonal, comma separated")
    ap.add_argument("--ridge-angle", type=float, default=30.0)
    ap.add_argument("--repeats", type=int, default=1, help="best of this many runs each")
    ap.add_argument("--out", default=str(REPO / "benchmarks" / "remesh_speed.md"))
    args = ap.parse_args()
    probe = large_input()
    input_faces = probe.current_mesh().face_number()
    diag = probe.current_mesh().bounding_box().diagonal()
    rows = ["| target (% diag) | input triangles | ours: faces | ours (s) | ours (tri/s) | MeshLab: faces | "
            "MeshLab (s) | MeshLab (tri/s) | throughput ratio (ours / MeshLab) | ours: open sides | ours: min angle |",
            "|---|---|---|---|---|---|---|---|---|---|---|"]
    for percent in (float(p) for p in args.percents.split(",")):
        length = pymeshlab.PureValue(percent / 100 * diag)
        ours = min((timed(lambda ms: ms.meshing_advancing_front_remesh(target_length=length,
                                                                        ridge_angle=args.ridge_angle))
                    for _ in range(args.repeats)), key=lambda r: r[0])
        iso = min((timed(lambda ms: ms.meshing_isotropic_explicit_remeshing(targetlen=length,
                                                                             featuredeg=args.ridge_angle))
                   for _ in range(args.repeats)), key=lambda r: r[0])
        rate_ours, rate_iso = ours[1] / ours[0], iso[1] / iso[0]
        rows.append(f"| {percent:g} | {input_faces} | {ours[1]} | {ours[0]:.2f} | {rate_ours:.0f} | {iso[1]} | "
                    f"{iso[0]:.2f} | {rate_iso:.0f} | {rate_ours / rate_iso:.2f} | {ours[2]['unmeshed_sides']} | "
                    f"{ours[2]['min_angle']:.1f} |")
        print(rows[-1], flush=True)
    text = "\n".join([
        "## Remeshing throughput on a large input (`scripts/bench_remesh_speed.py`)", "",
        f"Command: `.venv/bin/python scripts/bench_remesh_speed.py` — {datetime.date.today()}, {platform.machine()} "
        f"{platform.system()}, 2 cores; best of {args.repeats}. Input: organic/armadillo.off after two Loop "
        f"subdivisions ({input_faces} triangles). Ours: meshing_advancing_front_remesh with defaults; MeshLab: "
        f"meshing_isotropic_explicit_remeshing with its default iterations; same target length and feature angle "
        f"({args.ridge_angle:g} deg). Times are the filters only (the input is rebuilt before each run). "
        "Goal: ratio >= 1.", ""] + rows) + "\n"
    print(text)
    pathlib.Path(args.out).write_text(text)


if __name__ == "__main__":
    main()
