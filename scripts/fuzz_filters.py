#!/usr/bin/env python3
"""Bad inputs and bad parameters for every MeshRegrid filter: each call must return or refuse with
a PyMeshLabException, leave the input layer as it was, write no NaN, and never crash or hang.

Usage: .venv/bin/python scripts/fuzz_filters.py FIRST_SEED LAST_SEED [--timeout S]
Seeds run from FIRST_SEED up to LAST_SEED, which is left out (as in range()).
Seed s picks a filter (s % 5: features, remesh, union, healing, quad subdivision), an input
(s // 5 % 20: a shared mesh as it is, scaled to 1e150 or 1e-150, with a NaN or an infinite
coordinate, every face a repeated corner, a non-manifold fan, duplicated faces, two faces, three
equal points, a point cloud, an empty mesh, a triangle soup, a quad mesh, two overlapping
closed bodies, a mesh with unused vertices, half its faces flipped, offset by 1e12, a Moebius
strip, a 2000-face fan) and parameters drawn from the seed, in and out of
their ranges (remesh targets from 0.5%: smaller ones are slow, not wrong). The shared mesh
changes every 80 seeds (fandisk, bunny, rabbit.obj, angle_block.STL). Each case runs in its own
process, so a crash or a hang is seen as such. Prints one line per seed and the failing seeds at
the end; not part of the test suite (fuzz_remesh.py and fuzz_union.py damage the shared meshes
in more ways for those two filters).
"""
import pathlib
import sys

from fuzz_cases import run_seeds, seed_range

REPO = pathlib.Path(__file__).resolve().parents[1]
DATA = REPO.parent / "shared" / "data"
FILTERS = ["features", "remesh", "union", "healing", "quadsub"]
INPUTS = ["as it is", "scaled to 1e150", "scaled to 1e-150", "a NaN coordinate", "an infinite coordinate",
          "repeated corners", "non-manifold fan", "duplicated faces", "two faces", "three equal points",
          "point cloud", "empty", "triangle soup", "quad mesh", "two overlapping bodies", "unused vertices",
          "half the faces flipped", "offset by 1e12", "Moebius strip", "a 2000-face fan"]

CASE = r'''
import hashlib
import sys
import numpy as np
import meshregrid  # noqa: F401
import pymeshlab
seed, data = int(sys.argv[1]), sys.argv[2]
rng = np.random.default_rng(seed)
which, kind = seed % 5, seed // 5 % 20
ms = pymeshlab.MeshSet()


def add(v, f):
    v = np.asarray(v, dtype=np.float64).reshape(-1, 3)
    f = np.asarray(f, dtype=np.int32).reshape(-1, 3)
    if len(v) == 0:  # pymeshlab makes no mesh from empty arrays: a cube with its vertices removed
        ms.create_cube()
        ms.set_selection_all()
        ms.meshing_remove_selected_vertices()
        return
    ms.add_mesh(pymeshlab.Mesh(v, f) if len(f) else pymeshlab.Mesh(v))


def shared(name):
    m = pymeshlab.MeshSet()
    m.load_new_mesh(f"{data}/{name}")
    return m.current_mesh().vertex_matrix().copy(), m.current_mesh().face_matrix().copy()


base = ["cad/fandisk.obj", "organic/stanford-bunny.obj", "multicomponent/rabbit.obj", "healing/angle_block.STL"]
v, f = shared(base[seed // 80 % len(base)])
if kind == 13:
    ms.load_new_mesh(f"{data}/quad/torus_quad.off")
elif kind == 14:
    m = pymeshlab.MeshSet()
    m.create_sphere(subdiv=2)
    sv, sf = m.current_mesh().vertex_matrix(), m.current_mesh().face_matrix()
    add(np.concatenate([sv, sv + 0.3]), np.concatenate([sf, sf + len(sv)]))
else:
    if kind == 1:
        v = v * 1e150
    elif kind == 2:
        v = v * 1e-150
    elif kind == 3:
        v[int(rng.integers(len(v)))] = [np.nan, 0, 0]
    elif kind == 4:
        v[int(rng.integers(len(v)))] = [0, np.inf, 0]
    elif kind == 5:
        f[:, 1] = f[:, 0]
    elif kind == 6:
        v, f = [[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, -1, 0], [0, 0, 1]], [[0, 1, 2], [1, 0, 3], [0, 1, 4]]
    elif kind == 7:
        f = np.concatenate([f, f])
    elif kind == 8:
        f = f[:2]
    elif kind == 9:
        v, f = [[1, 1, 1]] * 3, [[0, 1, 2]]
    elif kind == 10:
        f = np.zeros((0, 3))
    elif kind == 11:
        v, f = np.zeros((0, 3)), np.zeros((0, 3))
    elif kind == 12:
        v, f = rng.random((90, 3)), np.arange(90).reshape(30, 3)
    elif kind == 15:
        v = np.concatenate([v, rng.random((50, 3))])
    elif kind == 16:
        f[::2] = f[::2, ::-1]
    elif kind == 17:
        v = v + 1e12
    elif kind == 18:  # a band of 40 quads with a half twist: P(2 pi, s) = P(0, -s)
        n, t = 40, np.linspace(0, 2 * np.pi, 40, endpoint=False)
        v = np.concatenate([np.stack([(1 + w * np.cos(t / 2)) * np.cos(t), (1 + w * np.cos(t / 2)) * np.sin(t),
                                      w * np.sin(t / 2)], 1) for w in (-0.3, 0.3)])
        f = [[i, n + i, n + i + 1] for i in range(n - 1)] + [[i, n + i + 1, i + 1] for i in range(n - 1)]
        f += [[n - 1, 2 * n - 1, 0], [n - 1, 0, n]]  # the last quad joins the sides crosswise
    elif kind == 19:  # one vertex with 2000 faces around it
        t = np.linspace(0, 2 * np.pi, 2000, endpoint=False)
        v = np.concatenate([[[0, 0, 0.2]], np.stack([np.cos(t), np.sin(t), 0 * t], 1)])
        f = np.array([[0, 1 + i, 1 + (i + 1) % 2000] for i in range(2000)])
    add(v, f)

pick = lambda *xs: xs[int(rng.integers(len(xs)))]
bad_parameters = rng.random() < 0.3  # else every parameter is in its range, so the mesh is what is tested


def value(good, bad):
    """A parameter value from `good`, or (in a bad-parameter case, half the time) from `bad`."""
    return pick(*bad) if bad_parameters and rng.random() < 0.5 else pick(*good)
shown = {}  # what each length parameter was, for the report


def length(key, good):
    """A length parameter: a percentage of the diagonal from `good`, or in a bad-parameter case
    0% or 100% or an absolute value that may be out of range (pymeshlab itself refuses
    percentages outside [0, 100])."""
    if not bad_parameters or rng.random() < 0.5:
        x = float(pick(*good) if not bad_parameters else pick(0, 100))
        shown[key] = f"{x}%"
        return pymeshlab.PercentageValue(x)
    x = float(pick(-1.0, 0.0, 1e-300, 0.01, 1e300, float("nan")))
    shown[key] = repr(x)
    return pymeshlab.PureValue(x)


def lengths(**kw):
    """Length parameters, each with its list of good percentages."""
    return {k: length(k, good) for k, good in kw.items()}

if which == 0:
    name, kw = "compute_feature_lines_and_patches", dict(
        ridge_angle=float(value([1, 30, 90, 179.9], [-10, 0, 180, 1e9])), corner_angle=float(value([0, 45, 180], [-1, 200])),
        min_patch_faces=int(value([0, 5], [-1, 10**9])), create_lines_layer=bool(pick(True, False)),
        **lengths(min_line_length=[0.1, 1, 5]))
elif which == 1:
    name, kw = "meshing_advancing_front_remesh", dict(
        ridge_angle=float(value([30, 60], [0, 180])), recovery=int(pick(0, 1, 2, 3)),
        gradation=float(value([1.3, 2], [0.5, 1e9])), **lengths(target_length=[0.5, 1, 5], min_line_length=[0.1, 1, 5]))
elif which == 2:
    name, kw = "generate_surface_intersection_union", dict(bodies=int(pick(0, 1)),
                                                              sliver_angle=float(value([0, 10, 45], [-5, 90])),
                                                              transfer_face_color=bool(pick(True, False)),
                                                              transfer_vert_quality=bool(pick(True, False)))
elif which == 3:
    name, kw = "meshing_heal_patch_gaps", dict(patch_source=int(pick(0, 1)),
                                               feature_angle=float(value([1, 30], [-1, 0, 180])),
                                               **lengths(vertex_tolerance=[0.01, 0.1, 1], edge_tolerance=[0, 0.1, 1]))
else:
    name, kw = "meshing_surface_subdivision_interpolatory_quad", dict(
        iterations=int(value([1, 2], [-1, 0, 9])), w=float(value([0, 1, 1.2], [-1, 1.5, 1e9])),
        crease_angle=float(value([0, 30], [-1, 180])), adaptive=int(pick(0, 1)), **lengths(error_threshold=[0.01, 0.1, 1]))

def snapshot(m):
    return hashlib.sha1(m.vertex_matrix().tobytes() + m.face_matrix().tobytes()).hexdigest()


print(f"calling {name} {dict(kw, **shown)}", flush=True)  # shown if the call then hangs
before = [snapshot(ms.mesh(i)) for i in range(ms.mesh_number())]
first = ms.mesh_number()
try:
    r = getattr(ms, name)(**kw)
    layers = [ms.mesh(i) for i in range(first, ms.mesh_number())] or [ms.current_mesh()]
    if any(not np.isfinite(m.vertex_matrix()).all() for m in layers if kind not in (3, 4)):
        print("NaN or infinite coordinates written")
        sys.exit(3)
    status = f"ok, {sum(m.face_number() for m in layers)} faces"
except pymeshlab.PyMeshLabException as e:
    status = "refused: " + str(e).strip().splitlines()[-1][:140]
    if [snapshot(ms.mesh(i)) for i in range(first)] != before:
        print("the input changed although the filter refused: " + status)
        sys.exit(4)
print(f"{name} {dict(kw, **shown)}: {status}")
'''


def main():
    seeds, timeout = seed_range(__doc__, 120)
    return run_seeds(CASE, seeds, lambda seed: (seed, DATA), lambda seed: f"{FILTERS[seed % 5]}, {INPUTS[seed // 5 % 20]}", timeout)


if __name__ == "__main__":
    sys.exit(main())
