#!/usr/bin/env python3
"""Convergence of the interpolatory quad subdivision (meshing_surface_subdivision_interpolatory_quad).

Samples smooth surfaces at steps h, h/2, h/4, h/8 (a height field z = cos(sqrt(x^2+y^2)) over
[0,1]^2 and a sphere built from a subdivided cube), subdivides each net with tension w = 1 and
measures the error of the new vertices against the exact surface (L1 = mean, and max). Prints a
table with the ratio between successive steps and writes benchmarks/quadsub_convergence.md.
On regular grids the scheme reproduces cubics, so away from the border the error of one step
falls like h^4 (ratio about 16).
"""
import argparse
import pathlib

import numpy as np

import meshregrid  # noqa: F401
import pymeshlab

REPO = pathlib.Path(__file__).resolve().parents[1]


def height(x, y):
    return np.cos(np.sqrt(x * x + y * y))


def grid_net(n):
    xs = np.linspace(0.0, 1.0, n + 1)
    v = np.array([[x, y, height(x, y)] for y in xs for x in xs])
    faces = [np.array([j * (n + 1) + i, j * (n + 1) + i + 1, (j + 1) * (n + 1) + i + 1, (j + 1) * (n + 1) + i],
                      dtype=np.uint32) for j in range(n) for i in range(n)]
    return v, faces


def sphere_net(n):
    """A cube's faces as n x n grids, projected on the unit sphere."""
    index, points, faces = {}, [], []
    def vertex(p):
        key = tuple(np.round(p * 2 * n).astype(int))
        if key not in index:
            index[key] = len(points)
            points.append(p / np.linalg.norm(p))
        return index[key]
    for axis in range(3):
        for sign in (-1.0, 1.0):
            u, w = (axis + 1) % 3, (axis + 2) % 3
            def at(i, j):
                p = np.zeros(3)
                p[axis], p[u], p[w] = sign, -1 + 2 * i / n, -1 + 2 * j / n
                return vertex(p)
            for i in range(n):
                for j in range(n):
                    quad = [at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)]
                    faces.append(np.array(quad if sign > 0 else quad[::-1], dtype=np.uint32))
    return np.array(points), faces


def subdivide(v, faces):
    # Through an OBJ file: PyMeshLab's polygon-list constructor rounds coordinates to float,
    # which would cap the measured error near 1e-8.
    import tempfile
    with tempfile.TemporaryDirectory() as tmp:
        path = pathlib.Path(tmp) / "net.obj"
        lines = ["v %.17g %.17g %.17g" % tuple(p) for p in v]
        lines += ["f " + " ".join(str(int(i) + 1) for i in f) for f in faces]
        path.write_text("\n".join(lines) + "\n")
        ms = pymeshlab.MeshSet()
        ms.load_new_mesh(str(path))
    ms.meshing_surface_subdivision_interpolatory_quad(iterations=1, w=1.0)
    return ms.current_mesh().vertex_matrix()[len(v):]  # the new vertices


def errors(kind, n):
    if kind == "height field":
        v, faces = grid_net(n)
        p = subdivide(v, faces)
        margin = 2.0 / n  # away from the border, where ghost points extrapolate linearly
        keep = (p[:, 0] >= margin) & (p[:, 0] <= 1 - margin) & (p[:, 1] >= margin) & (p[:, 1] <= 1 - margin)
        err = np.abs(p[keep, 2] - height(p[keep, 0], p[keep, 1]))
    else:
        v, faces = sphere_net(n)
        p = subdivide(v, faces)
        err = np.abs(np.linalg.norm(p, axis=1) - 1.0)
    return float(err.mean()), float(err.max())


def table(steps):
    rows = ["| surface | 1/h | L1 error | max error | L1 ratio | max ratio |", "|---|---|---|---|---|---|"]
    results = {}
    for kind in ("height field", "sphere"):
        previous = None
        for n in steps:
            l1, mx = errors(kind, n)
            results[(kind, n)] = (l1, mx)
            ratio = ("%.2f" % (previous[0] / l1), "%.2f" % (previous[1] / mx)) if previous else ("", "")
            rows.append(f"| {kind} | {n} | {l1:.3e} | {mx:.3e} | {ratio[0]} | {ratio[1]} |")
            previous = (l1, mx)
    return rows, results


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--coarsest", type=int, default=8, help="1/h of the coarsest net (default 8)")
    ap.add_argument("--out", default=str(REPO / "benchmarks" / "quadsub_convergence.md"))
    args = ap.parse_args()
    steps = [args.coarsest * 2 ** k for k in range(4)]
    rows, _ = table(steps)
    text = "\n".join(["## Interpolatory quad subdivision: convergence (`scripts/convergence_quad.py`)", "",
                      "Error of the new vertices of one step (w = 1) against the exact surface.", ""] + rows) + "\n"
    print(text)
    pathlib.Path(args.out).write_text(text)


if __name__ == "__main__":
    main()
