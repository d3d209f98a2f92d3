#!/usr/bin/env python3
"""Union then regrid on fuzz_union's --models cases: checks and smallest angles per seed.

    .venv/bin/python scripts/fuzz_union_regrid.py FIRST LAST [--percent P] [--relax-wedges]
        [--out SEEDS.jsonl] [--compare BASELINE.jsonl]

Each seed unites a shared CAD or scan model with turned, shifted or mirrored copies of itself
(`fuzz_union.models_case`), then regrids the union with `pipeline_union.union(remesh=True)`.
A seed fails when the pipeline raises, or the regrid is open, not two-manifold or leaves sides
unmeshed. Every seed's smallest angle, smallest angle off the wedges and face count go to
`--out` (one JSON object a line); `--compare` reads an earlier such file and lists the seeds
whose angles changed, better first by the smallest angle, then by the one off the wedges.
Exit status 1 when a seed failed. The development records' "seeds 0-95 at 1%" are this script.
"""
import argparse
import json
import pathlib
import sys
import time

import pymeshlab

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
import fuzz_union  # noqa: E402  (the --models cases)
import meshregrid  # noqa: E402,F401  (loads the plugins)
from meshregrid import pipeline_union  # noqa: E402

SAME = 1e-6  # degrees: angles closer than this are the same
# MeshSets whose filter raised, kept until the end: PyMeshLab 2025.07 keeps a pointer to such a
# set's log, and a later load elsewhere could write to it once the set is freed (README).
_RAISED = []


def run_seed(seed, models, percent, relax):
    kind, parts = fuzz_union.models_case(seed, models)
    ms = pymeshlab.MeshSet()
    for v, f in parts:
        ms.add_mesh(pymeshlab.Mesh(v, f))
    t = time.perf_counter()
    out = {"seed": seed, "model": fuzz_union.MODELS[kind]}
    try:
        r = pipeline_union.union(ms, remesh=True, target_percent=percent, relax_wedges=relax)
    except pymeshlab.PyMeshLabException as e:
        _RAISED.append(ms)
        out["error"] = str(e).splitlines()[0]
        return out
    rr = r["remesh"]
    topo = ms.get_topological_measures()
    out.update(min=rr["min_angle"], off=rr["min_angle_off_wedges"], faces=ms.current_mesh().face_number(),
               from_exact_union=rr["from_exact_union"], seconds=round(time.perf_counter() - t, 2))
    problems = []
    if topo["boundary_edges"]:
        problems.append(f"{topo['boundary_edges']} boundary edges")
    if not topo["is_mesh_two_manifold"]:
        problems.append("not two-manifold")
    if rr["unmeshed_sides"]:
        problems.append(f"{rr['unmeshed_sides']} unmeshed sides")
    if problems:
        out["error"] = ", ".join(problems)
    return out


def compare(baseline_path, results):
    """Seeds whose angles differ from the baseline's, and a one-line count."""
    base = {}
    for line in pathlib.Path(baseline_path).read_text().splitlines():
        if line.strip():
            row = json.loads(line)
            base[row["seed"]] = row
    better = worse = same = 0
    for row in results:
        old = base.get(row["seed"])
        if old is None or "error" in old or "error" in row:
            continue
        d, d_off = row["min"] - old["min"], row["off"] - old["off"]
        if abs(d) < SAME and abs(d_off) < SAME:
            same += 1
            continue
        up = d > SAME or (abs(d) <= SAME and d_off > 0)
        better += up
        worse += not up
        print(f"seed {row['seed']} ({row['model']}) {'better' if up else 'worse'}: "
              f"{old['min']:.2f} -> {row['min']:.2f}, off the wedges {old['off']:.2f} -> {row['off']:.2f}, "
              f"faces {old.get('faces', '?')} -> {row['faces']}")
    print(f"against {baseline_path}: {better} better, {worse} worse, {same} the same")


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("first", type=int)
    ap.add_argument("last", type=int, help="one past the last seed")
    ap.add_argument("--percent", type=float, default=1.0, help="target length, percent of the diagonal")
    ap.add_argument("--relax-wedges", action="store_true")
    ap.add_argument("--out", help="write one JSON line per seed here")
    ap.add_argument("--compare", help="an earlier --out file to compare with")
    args = ap.parse_args()
    models = fuzz_union.load_models()
    results, failed = [], 0
    sink = open(args.out, "w") if args.out else None
    for seed in range(args.first, args.last):
        row = run_seed(seed, models, args.percent, args.relax_wedges)
        results.append(row)
        if sink:
            sink.write(json.dumps(row) + "\n")
            sink.flush()
        if "error" in row:
            failed += 1
            print(f"seed {seed} ({row['model']}): {row['error']}", flush=True)
    if sink:
        sink.close()
    angles = sorted(r["min"] for r in results if "min" in r)
    if angles:
        print(f"{len(results)} seeds, {failed} failures; smallest angle: median {angles[len(angles) // 2]:.2f}, "
              f"{sum(a >= 30 for a in angles)} at 30 or more, {sum(a < 5 for a in angles)} under 5")
    else:
        print(f"{len(results)} seeds, {failed} failures")
    if args.compare:
        compare(args.compare, results)
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
