#!/usr/bin/env python3
"""Ours (meshing_advancing_front_remesh) vs MeshLab's meshing_isotropic_explicit_remeshing,
in the same run, at the same target length (default 1% of the diagonal) and feature angle,
on the organic and CAD meshes of ../shared/data. Optional peers when importable: Netgen's
STL surface mesher (netgen-mesher) and MMG's surface remesher (mmgpy). The row
ours_relax_wedges is our filter with the opt-in relax_wedges.

Writes <out>/remesh_compare.json, <out>/remesh_compare.md, <out>/remesh_min_angle_hist.png
and, with --benchmark-md, benchmarks/remesh.md.

    MESHREGRID_PLUGIN_DIR=build/plugins .venv/bin/python scripts/compare_isotropic.py

With --faces N each mesh gets the target length that gives about N equilateral output triangles
over its area instead (the issue measured Netgen's quality on a CAD part at about 200k output
triangles); --benchmark-md then writes benchmarks/remesh_<N/1000>k.md.
"""
import argparse
import datetime
import json
import os
import pathlib
import platform
import subprocess
import sys
import tempfile
import time

import numpy as np

REPO = pathlib.Path(__file__).resolve().parents[1]
sys.path.insert(0, str(REPO / "python"))
import meshregrid  # noqa: E402,F401  (loads the plugins)
from meshregrid.quality import hausdorff  # noqa: E402
import pymeshlab  # noqa: E402

DATA = REPO.parent / "shared" / "data"
MESHES = ["cad/part.off", "cad/joint.off", "cad/fandisk.obj", "cad/blade.off", "organic/rocker-arm.obj",
          "organic/armadillo.off", "organic/stanford-bunny.obj"]


def face_angles(v, f):
    t = v[f]

    def angle(a, b, c):
        u, w = b - a, c - a
        return np.degrees(np.arctan2(np.linalg.norm(np.cross(u, w), axis=1), (u * w).sum(1)))

    return np.stack([angle(t[:, 0], t[:, 1], t[:, 2]), angle(t[:, 1], t[:, 2], t[:, 0]),
                     angle(t[:, 2], t[:, 0], t[:, 1])], 1)


def radius_ratio(v, f):
    """2r/R per face (1 for equilateral)."""
    t = v[f]
    a = np.linalg.norm(t[:, 1] - t[:, 2], axis=1)
    b = np.linalg.norm(t[:, 2] - t[:, 0], axis=1)
    c = np.linalg.norm(t[:, 0] - t[:, 1], axis=1)
    s = 0.5 * (a + b + c)
    area = 0.5 * np.linalg.norm(np.cross(t[:, 1] - t[:, 0], t[:, 2] - t[:, 0]), axis=1)
    r = area / np.maximum(s, 1e-300)
    big_r = a * b * c / np.maximum(4 * area, 1e-300)
    return np.where(area > 0, 2 * r / np.maximum(big_r, 1e-300), 0.0)


def seg_distance(p, a, b):
    if len(a) == 0:
        return np.full(len(p), np.inf)
    best = np.full(len(p), np.inf)
    d = b - a
    len2 = np.maximum((d * d).sum(1), 1e-300)
    for s in range(0, len(p), 128):
        q = p[s:s + 128, None, :]
        t = np.clip(((q - a[None]) * d[None]).sum(2) / len2[None], 0, 1)
        best[s:s + 128] = np.linalg.norm(a[None] + t[..., None] * d[None] - q, axis=2).min(1)
    return best


def ridges(mesh, angle):
    """Ridge segments of a mesh (feature filter's lines layer)."""
    ms = pymeshlab.MeshSet()
    ms.add_mesh(mesh)
    ms.compute_feature_lines_and_patches(ridge_angle=angle, create_lines_layer=True, color_patches=False)
    layer = ms.mesh(1)
    v, e = layer.vertex_matrix(), layer.edge_matrix()
    if len(e) == 0:
        return np.zeros((0, 3)), np.zeros((0, 3))
    return v[e[:, 0]], v[e[:, 1]]


def measure(ms, mid, ref_id, diag, target, angle, in_ridges, seconds):
    m = ms.mesh(mid)
    v, f = m.vertex_matrix(), m.face_matrix()
    ang = face_angles(v, f)
    mins = ang.min(1)
    rr = radius_ratio(v, f)
    e = np.unique(np.sort(np.concatenate([f[:, [0, 1]], f[:, [1, 2]], f[:, [2, 0]]]), axis=1), axis=0)
    lengths = np.linalg.norm(v[e[:, 0]] - v[e[:, 1]], axis=1)
    ms.set_current_mesh(mid)
    topo = ms.get_topological_measures()
    valence = np.bincount(e.ravel(), minlength=len(v))
    counts = np.bincount(np.concatenate([e[:, 0], e[:, 1]]), minlength=len(v))
    # Interior vertices only: boundary vertices have other ideal valences.
    directed = np.concatenate([f[:, [0, 1]], f[:, [1, 2]], f[:, [2, 0]]])
    und, n = np.unique(np.sort(directed, axis=1), axis=0, return_counts=True)
    boundary_v = np.unique(und[n == 1].ravel())
    interior = np.setdiff1d(np.arange(len(v)), boundary_v)
    # Many samples: with 20k the maximum moved by ~10% between runs.
    h = hausdorff(ms, mid, ref_id, max(20 * len(f), 200000))
    out_a, out_b = ridges(m, angle)
    tol = 0.05 * target
    in_a, in_b = in_ridges
    missed = float(np.mean(seg_distance(0.5 * (in_a + in_b), out_a, out_b) > tol)) if len(in_a) else 0.0
    spurious = float(np.mean(seg_distance(0.5 * (out_a + out_b), in_a, in_b) > tol)) if len(out_a) else 0.0
    del valence
    return {
        "time_s": seconds, "faces": int(len(f)),
        "min_angle": float(mins.min()), "p1_min_angle": float(np.percentile(mins, 1)),
        "mean_min_angle": float(mins.mean()), "below_30": float(np.mean(mins < 30)),
        "rr_min": float(rr.min()), "rr_mean": float(rr.mean()),
        "valence6": float(np.mean(counts[interior] == 6)) if len(interior) else 0.0,
        "edge_spread": float(lengths.std() / lengths.mean()),
        "edges_in_range": float(np.mean((lengths >= 0.7 * target) & (lengths <= 1.4 * target))),
        "hausdorff_rel": float(h / diag),
        "ridges_missed": missed, "spurious_feature_edges": spurious,
        "manifold": bool(topo["non_two_manifold_edges"] == 0 and topo["non_two_manifold_vertices"] == 0),
        "boundary_loops": int(topo["number_holes"]), "genus": int(topo["genus"]),
        "components": int(topo["connected_components_number"]),
        "_min_angles": mins,
    }


def peer_worker(peer, src, dst, target, angle):
    """Runs one peer on the arrays in `src` (npz: v, f) and writes its mesh and time to `dst`.
    Called in a child process: a peer that crashes (Netgen's STL mesher does on cad/blade.off)
    takes only the child down."""
    data = np.load(src)
    v, f = data["v"], data["f"]
    if peer == "netgen":
        import netgen.meshing
        import netgen.stl
        with tempfile.TemporaryDirectory() as tmp:
            stl = os.path.join(tmp, "in.stl")
            ms = pymeshlab.MeshSet()
            ms.add_mesh(pymeshlab.Mesh(v, f))
            ms.save_current_mesh(stl)
            t = time.perf_counter()
            geo = netgen.stl.STLGeometry(stl)
            mesh = geo.GenerateMesh(maxh=target, yangle=angle, perfstepsend=netgen.meshing.MeshingStep.MESHSURFACE)
            secs = time.perf_counter() - t
        pts = np.array([p.p for p in mesh.Points()])
        tris = np.array([[q.nr - 1 for q in el.vertices] for el in mesh.Elements2D()])
    elif peer == "mmg":
        import mmgpy
        t = time.perf_counter()
        mesh = mmgpy.MmgMeshS(np.ascontiguousarray(v, dtype=float), np.ascontiguousarray(f, dtype=np.int32))
        mesh.remesh(hsiz=target, hausd=0.1 * target, ar=angle, verbose=-1)  # in place
        pts, tris = np.asarray(mesh.get_vertices()), np.asarray(mesh.get_triangles())
        secs = time.perf_counter() - t
    else:
        raise ValueError(f"unknown peer {peer}")
    np.savez(dst, v=pts, f=tris, seconds=secs)


def peer_available(peer):
    module = {"netgen": "netgen.stl", "mmg": "mmgpy"}[peer]
    try:
        __import__(module)
        return True
    except ImportError:
        return False


def run_peers(ms, target, angle, diag, in_ridges, src_id, ref_id, peers):
    """Netgen and MMG when installed (python/requirements-peers.txt) and asked for, each in a child
    process; measured like ours. Netgen's time includes reading the STL it needs, MMG's the
    conversion to and from its arrays. A peer that fails or crashes is reported and left out."""
    out = {}
    m = ms.mesh(src_id)
    with tempfile.TemporaryDirectory() as tmp:
        src = os.path.join(tmp, "in.npz")
        np.savez(src, v=m.vertex_matrix(), f=m.face_matrix())
        for peer in peers:
            if not peer_available(peer):
                continue
            dst = os.path.join(tmp, f"{peer}.npz")
            run = subprocess.run([sys.executable, __file__, "--peer-worker", peer, src, dst, repr(target), repr(angle)],
                                 capture_output=True, text=True, timeout=3600)
            if run.returncode != 0 or not os.path.exists(dst):
                why = f"signal {-run.returncode}" if run.returncode < 0 else (run.stderr.strip().splitlines() or ["?"])[-1]
                print(f"  {peer} failed: {why}", file=sys.stderr)
                continue
            res = np.load(dst)
            ms.add_mesh(pymeshlab.Mesh(res["v"], res["f"]))
            out[peer] = measure(ms, ms.current_mesh_id(), ref_id, diag, target, angle, in_ridges, float(res["seconds"]))
    return out


def goals_table(rows):
    """Issue #3's goal per mesh: Netgen's element quality (mean per-triangle minimum angle >= 57,
    >= 95% valence-6 vertices) at MeshLab's speed or better, with the time ratios of this run."""
    by = {(r["mesh"], r["method"]): r for r in rows}
    lines = ["", "Goal (issue #3): mean minimum angle >= 57 and valence-6 share >= 0.95 (Netgen's quality), "
             "time <= MeshLab's.", "",
             "| mesh | ours / MeshLab time | ours / Netgen time | ours mean min angle | Netgen mean min angle | "
             "ours valence6 | Netgen valence6 | goal met |", "|---|---|---|---|---|---|---|---|"]
    for mesh in dict.fromkeys(r["mesh"] for r in rows):
        ours, iso, ng = by.get((mesh, "ours")), by.get((mesh, "meshlab_isotropic")), by.get((mesh, "netgen"))
        if not ours or not iso:
            continue
        peer = (lambda key, f: f.format(ng[key]) if ng else "—")  # noqa: E731  (Netgen may be absent or crash)
        met = ours["mean_min_angle"] >= 57 and ours["valence6"] >= 0.95 and ours["time_s"] <= iso["time_s"]
        ratio_ng = f"{ours['time_s'] / ng['time_s']:.2f}" if ng else "—"
        lines.append(f"| {mesh} | {ours['time_s'] / iso['time_s']:.2f} | {ratio_ng} | {ours['mean_min_angle']:.2f} | "
                     f"{peer('mean_min_angle', '{:.2f}')} | {ours['valence6']:.3f} | {peer('valence6', '{:.3f}')} | {met} |")
    return "\n".join(lines) + "\n"


def main(argv=None):
    argv = sys.argv[1:] if argv is None else argv
    if argv[:1] == ["--peer-worker"]:
        peer_worker(argv[1], argv[2], argv[3], float(argv[4]), float(argv[5]))
        return 0
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--meshes", nargs="*", default=MESHES, help="paths relative to ../shared/data")
    ap.add_argument("--percent", type=float, default=1.0, help="target length in %% of the diagonal (default 1)")
    ap.add_argument("--faces", type=int, default=0,
                    help="instead of --percent: per mesh, the target length for about this many output triangles")
    ap.add_argument("--ridge-angle", type=float, default=30.0)
    ap.add_argument("--min-line", type=float, default=2.0,
                    help="our min_line_length in units of the target length (default 2, the filter's default; "
                         "0 keeps every ridge)")
    ap.add_argument("--out", default="out/compare_isotropic")
    ap.add_argument("--peers", default="netgen,mmg",
                    help="optional peers to run when installed (comma list of netgen, mmg; empty for none)")
    ap.add_argument("--benchmark-md", action="store_true", help="also write benchmarks/remesh.md")
    ap.add_argument("--allow-missing-peers", action="store_true",
                    help="with --benchmark-md: write the table although a peer asked for is not installed")
    args = ap.parse_args(argv)
    # A peer asked for but not installed is said, not silently left out: a table written without it
    # would replace one that had it.
    missing = [peer for peer in filter(None, args.peers.split(",")) if not peer_available(peer)]
    if missing:
        print(f"peers not installed, left out: {', '.join(missing)} "
              "(pip install -r python/requirements-peers.txt)", file=sys.stderr)
        if args.benchmark_md and not args.allow_missing_peers:
            print("not writing benchmarks/ without them; --allow-missing-peers writes it anyway", file=sys.stderr)
            return 2
    out = pathlib.Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    rows, hist = [], {}
    for name in args.meshes:
        path = DATA / name
        if not path.is_file():
            print(f"skip {name}: not found", file=sys.stderr)
            continue
        ms = pymeshlab.MeshSet()
        ms.load_new_mesh(str(path))
        src_id = ms.current_mesh_id()
        # The Hausdorff reference is the input's surface: scans such as the bunny carry vertices no
        # face uses (1113 of them), which are no part of the surface either method remeshes.
        ms.generate_copy_of_current_mesh()
        ms.meshing_remove_unreferenced_vertices()
        ref_id = ms.current_mesh_id()
        ms.set_current_mesh(src_id)
        diag = ms.current_mesh().bounding_box().diagonal()
        target = args.percent / 100 * diag
        if args.faces > 0:  # equilateral triangles of side L have area sqrt(3)/4 L^2
            area = ms.get_geometric_measures()["surface_area"]
            target = float(np.sqrt(4 * area / (np.sqrt(3) * args.faces)))
        in_ridges = ridges(ms.current_mesh(), args.ridge_angle)
        t = time.perf_counter()
        res = ms.meshing_advancing_front_remesh(target_length=pymeshlab.PureValue(target), ridge_angle=args.ridge_angle,
                                                min_line_length=pymeshlab.PureValue(args.min_line * target))
        ours = measure(ms, ms.current_mesh_id(), ref_id, diag, target, args.ridge_angle, in_ridges, time.perf_counter() - t)
        ours["unmeshed_sides"] = res["unmeshed_sides"]
        # The same with the opt-in wedge relaxing: lines leaving a point at under 30 degrees may
        # share their first segment (docs/remesh.md, "Wedges of feature lines").
        ms.set_current_mesh(src_id)
        t = time.perf_counter()
        res = ms.meshing_advancing_front_remesh(target_length=pymeshlab.PureValue(target), ridge_angle=args.ridge_angle,
                                                min_line_length=pymeshlab.PureValue(args.min_line * target),
                                                relax_wedges=True)
        relaxed = measure(ms, ms.current_mesh_id(), ref_id, diag, target, args.ridge_angle, in_ridges,
                          time.perf_counter() - t)
        relaxed["unmeshed_sides"] = res["unmeshed_sides"]
        ms.set_current_mesh(src_id)
        ms.generate_copy_of_current_mesh()
        t = time.perf_counter()
        ms.meshing_isotropic_explicit_remeshing(targetlen=pymeshlab.PureValue(target), featuredeg=args.ridge_angle)
        iso = measure(ms, ms.current_mesh_id(), ref_id, diag, target, args.ridge_angle, in_ridges, time.perf_counter() - t)
        ms.set_current_mesh(src_id)
        src_topo = ms.get_topological_measures()
        results = {"ours": ours, "ours_relax_wedges": relaxed, "meshlab_isotropic": iso}
        results.update(run_peers(ms, target, args.ridge_angle, diag, in_ridges, src_id, ref_id,
                                 [p for p in args.peers.split(",") if p]))
        for method, r in results.items():
            hist[(name, method)] = r.pop("_min_angles")
            # Boundary loops, not boundary edges: a remeshed border has another number of edges.
            # PyMeshLab reports -1 loops and genus on a non-manifold mesh, so that never matches.
            r["topology_kept"] = bool(r["boundary_loops"] == src_topo["number_holes"] and r["genus"] == src_topo["genus"]
                                      and r["components"] == src_topo["connected_components_number"])
            rows.append({"mesh": name, "method": method, **r})
        print(f"{name}: ours {ours['time_s']:.2f}s min {ours['min_angle']:.1f} | isotropic {iso['time_s']:.2f}s "
              f"min {iso['min_angle']:.1f}", file=sys.stderr)

    (out / "remesh_compare.json").write_text(json.dumps(rows, indent=2))
    cols = ["mesh", "method", "time_s", "faces", "min_angle", "p1_min_angle", "mean_min_angle", "below_30", "rr_min",
            "rr_mean", "valence6", "edge_spread", "edges_in_range", "hausdorff_rel", "ridges_missed",
            "spurious_feature_edges", "manifold", "topology_kept"]
    fmt = lambda x: f"{x:.4g}" if isinstance(x, float) else str(x)  # noqa: E731
    table = ["| " + " | ".join(cols) + " |", "|" + "---|" * len(cols)]
    table += ["| " + " | ".join(fmt(r[c]) for c in cols) + " |" for r in rows]
    md = "\n".join(table) + "\n" + goals_table(rows)
    (out / "remesh_compare.md").write_text(md)

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    names = list(dict.fromkeys(n for n, _ in hist))
    fig, axes = plt.subplots(len(names), 1, figsize=(7, 2.2 * max(len(names), 1)), squeeze=False)
    for ax, n in zip(axes[:, 0], names):
        for (mn, method), a in hist.items():
            if mn == n:
                ax.hist(a, bins=60, range=(0, 60), histtype="step", density=True, label=method)
        ax.set_title(n, fontsize=9)
        ax.legend(fontsize=7)
    axes[-1, 0].set_xlabel("triangle minimum angle (degrees)")
    fig.tight_layout()
    fig.savefig(out / "remesh_min_angle_hist.png", dpi=80)
    print(md)
    if args.benchmark_md:
        cmd = ("MESHREGRID_PLUGIN_DIR=build/plugins .venv/bin/python scripts/compare_isotropic.py --benchmark-md"
               + (f" --faces {args.faces}" if args.faces > 0 else "")
               + (f" --meshes {' '.join(args.meshes)}" if args.meshes != MESHES else "")
               + (f" --peers '{args.peers}'" if args.peers != "netgen,mmg" else ""))
        size = (f"Target length per mesh for about {args.faces} equilateral output triangles over its area"
                if args.faces > 0 else f"Target length {args.percent}% of the bounding-box diagonal")
        title = f" at about {args.faces // 1000}k output triangles" if args.faces > 0 else ""
        text = (f"# Advancing-front remeshing vs MeshLab isotropic remeshing{title}\n\n"
                f"Command: `{cmd}`  \nMachine: {platform.processor() or platform.machine()}, {os.cpu_count()} cores, "
                f"{platform.system()}  \nDate: {datetime.datetime.now(datetime.timezone.utc):%Y-%m-%d %H:%M} UTC  \n"
                f"{size}, ridge/feature angle {args.ridge_angle} deg, "
                f"our min_line_length {args.min_line} x target. "
                f"Times include the filters only. Peers Netgen and MMG (python/requirements-peers.txt) run each in "
                f"a child process; a crash is left out of the table. Hausdorff: two-sided, PyMeshLab sampling, over "
                f"the diagonal, against "
                f"the input without unreferenced vertices (the bunny scan has 1113). "
                f"Feature fidelity: share of ridge segments farther than 5% of the target from the other side's ridges "
                f"(input ridges: every {args.ridge_angle}-degree ridge, min_line_length 0). "
                f"topology_kept: same boundary loops (PyMeshLab number_holes), genus and components as the input.\n\n"
                + md + f"\nMinimum-angle histograms: `{out / 'remesh_min_angle_hist.png'}`.\n")
        name = f"remesh_{args.faces // 1000}k.md" if args.faces > 0 else "remesh.md"
        (REPO / "benchmarks" / name).write_text(text)
    return 0


if __name__ == "__main__":
    sys.exit(main())
