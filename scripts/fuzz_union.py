#!/usr/bin/env python3
"""Random unions with many degenerate contacts, checked against manifold3d.

Usage: .venv/bin/python scripts/fuzz_union.py FIRST_SEED LAST_SEED [--nonconvex | --selfcrossing | --models] [--params] [--transform]
Seeds run from FIRST_SEED up to LAST_SEED, which is left out (as in range()).
Each seed builds 2-7 bodies of one kind: grid-aligned cubes (coplanar faces, shared edges,
touching), spheres on a 0.1 grid (identical copies, touching poles), subdivided cubes and
spheres on a quarter grid, spheres of several radii sharing centres and poles, randomly rotated
cubes. With --nonconvex the bodies are not convex: spheres with radial noise (blobs), rotated
tori (not star-shaped), and a blob with copies of itself scaled about one of its vertices or
shifted on a grid (coincident and nearly coincident faces).
With --models the bodies are one of the shared CAD and organic models (cad/joint.off, cad/part.off,
cad/fandisk.obj, organic/rocker-arm.obj, beside the repository) and one or two copies of it
turned at random, by quarter turns (nearly coincident faces where the model is symmetric) or
only shifted on a grid.
With --params the run with the sliver step draws its parameters from the seed instead of the
defaults (sliver angle 1-59 deg, deviation 1e-5 to 1e-1 of the diagonal, volume budget 1e-9 to
1e-3), and the volume must then be within the budget drawn.
With --transform the bodies are scaled by 2^k (k from -60 to 60: exact) and moved 10 to 1e5 times
their scale away from the origin (the one rounding), so the exact predicates meet wide exponent
spreads. Volumes and crossings are measured on the results moved back and scaled down again,
which is exact there (Sterbenz), so the checks keep their tolerances.
With --selfcrossing one body is a blob and a shifted copy of it in one layer (it crosses
itself), among good blobs cut by it: the union must refuse it by name, whatever its steps did
with it meanwhile (the self-intersection check runs beside the sliver step), and not crash.
Each is united with the sliver step off and on and must give no error, a closed two-manifold
surface and manifold3d's volume (cavities filled): 1e-9 relative without the sliver step, its
volume budget (1e-6) with it. With the sliver step (the default) the result must also have no
face with two corners at one place and no face that MeshLab's self-intersection selection
flags and exact rationals confirm (meshregrid.quality.exactly_intersecting_faces). Where only the volume differs, MeshLab's union (libigl on CGAL's
exact kernel) arbitrates: manifold3d perturbs coincident geometry symbolically. Prints the
failing seeds; not part of the test suite.
"""
import pathlib
import sys

import numpy as np

import meshregrid  # noqa: F401
from meshregrid.quality import exactly_intersecting_faces
import manifold3d
import pymeshlab


def reference(parts):
    ps = [manifold3d.Manifold(manifold3d.Mesh64(vert_properties=np.ascontiguousarray(v, dtype=np.float64),
                                                tri_verts=np.ascontiguousarray(f, dtype=np.uint64))) for v, f in parts]
    union = manifold3d.Manifold.batch_boolean(ps, manifold3d.OpType.Add)
    return sum(c.volume() for c in union.decompose() if c.volume() > 0)


def meshlab_union_volume(parts):
    ms = pymeshlab.MeshSet()
    for v, f in parts:
        ms.add_mesh(pymeshlab.Mesh(v, f))
    current = 0
    for i in range(1, len(parts)):
        ms.generate_boolean_union(first_mesh=current, second_mesh=i)
        current = ms.current_mesh_id()
    ms.set_current_mesh(current)
    return ms.get_geometric_measures()["mesh_volume"]


def shapes():
    ms = pymeshlab.MeshSet()
    ms.create_cube(size=1)
    cube = (ms.current_mesh().vertex_matrix(), ms.current_mesh().face_matrix())
    ms.create_sphere(radius=0.5, subdiv=2)
    sphere = (ms.current_mesh().vertex_matrix(), ms.current_mesh().face_matrix())
    ms.create_cube(size=1)
    ms.meshing_surface_subdivision_midpoint(iterations=1)
    cube2 = (ms.current_mesh().vertex_matrix(), ms.current_mesh().face_matrix())
    return cube, sphere, cube2


def case(seed, cube, sphere, cube2):
    rng = np.random.default_rng(seed)
    kind = seed % 5
    parts = []
    for _ in range(rng.integers(2, 8)):
        if kind == 0:
            off = rng.integers(0, 4, 3) * 0.5
            parts.append((cube[0] * rng.integers(1, 3) + off, cube[1]))
        elif kind == 1:
            parts.append((sphere[0] + np.round(rng.random(3) * 1.5, 1), sphere[1]))
        elif kind == 3:
            off = rng.integers(0, 6, 3) * 0.25
            parts.append((cube2[0] + off, cube2[1]) if rng.random() < 0.7 else (sphere[0] + off, sphere[1]))
        elif kind == 4:
            centre = rng.integers(0, 3, 3) * 0.5
            parts.append((sphere[0] * rng.choice([0.5, 1.0, 1.5]) * 2 + centre, sphere[1]))
        else:
            a = rng.random(3) * np.pi
            rx = np.array([[1, 0, 0], [0, np.cos(a[0]), -np.sin(a[0])], [0, np.sin(a[0]), np.cos(a[0])]])
            rz = np.array([[np.cos(a[2]), -np.sin(a[2]), 0], [np.sin(a[2]), np.cos(a[2]), 0], [0, 0, 1]])
            parts.append((cube[0] @ (rz @ rx).T + rng.random(3), cube[1]))
    return kind, parts


def rotation(rng):
    a = rng.random(3) * 2 * np.pi
    rx = np.array([[1, 0, 0], [0, np.cos(a[0]), -np.sin(a[0])], [0, np.sin(a[0]), np.cos(a[0])]])
    ry = np.array([[np.cos(a[1]), 0, np.sin(a[1])], [0, 1, 0], [-np.sin(a[1]), 0, np.cos(a[1])]])
    rz = np.array([[np.cos(a[2]), -np.sin(a[2]), 0], [np.sin(a[2]), np.cos(a[2]), 0], [0, 0, 1]])
    return rz @ ry @ rx


def nonconvex_case(seed, sphere, torus):
    rng = np.random.default_rng(seed)
    kind = seed % 3

    def blob(scale):
        v, f = sphere
        return v * (1 + rng.uniform(-0.3, 0.3, (len(v), 1))) * 2 * scale, f

    parts = []
    if kind == 2:  # a blob and copies of it scaled about one of its vertices or shifted
        v, f = blob(rng.choice([0.5, 1.0]))
        v = v + np.round(rng.random(3), 1)
        parts.append((v, f))
        for _ in range(rng.integers(1, 4)):
            if rng.random() < 0.5:
                p = v[rng.integers(len(v))]
                parts.append(((v - p) * rng.choice([0.5, 0.75, 1.5]) + p, f))
            else:
                parts.append((v + rng.integers(-2, 3, 3) * 0.125, f))
        return kind, parts
    for _ in range(rng.integers(2, 6)):
        if kind == 0:
            v, f = blob(rng.uniform(0.3, 0.8))
            parts.append((v + np.round(rng.random(3) * 1.5, 1), f))
        else:
            v, f = torus
            parts.append((v * rng.uniform(0.4, 1.0) @ rotation(rng).T + rng.random(3) * 1.5, f))
    return kind, parts


def selfcrossing_case(seed, sphere):
    """A blob and its copy shifted by less than its size, as one body, among good blobs."""
    rng = np.random.default_rng(seed)
    v, f = sphere
    v = v * (1 + rng.uniform(-0.3, 0.3, (len(v), 1))) * 2 * rng.uniform(0.3, 0.8)
    shift = rng.uniform(-0.35, 0.35, 3)
    twin = (np.concatenate([v, v + shift]), np.concatenate([f, f + len(v)]))
    parts = []
    for _ in range(rng.integers(1, 4)):
        w = sphere[0] * (1 + rng.uniform(-0.3, 0.3, (len(sphere[0]), 1))) * 2 * rng.uniform(0.3, 0.8)
        parts.append((w + rng.uniform(-0.5, 0.5, 3), sphere[1]))
    at = int(rng.integers(0, len(parts) + 1))
    parts.insert(at, twin)
    return at, parts


MODELS = ["cad/joint.off", "cad/part.off", "cad/fandisk.obj", "organic/rocker-arm.obj"]


def load_models():
    root = pathlib.Path(__file__).resolve().parent.parent.parent / "shared" / "data"
    if not root.is_dir():
        sys.exit(f"--models needs the shared meshes beside the repository ({root})")
    out = []
    for name in MODELS:
        ms = pymeshlab.MeshSet()
        ms.load_new_mesh(str(root / name))
        out.append((ms.current_mesh().vertex_matrix(), ms.current_mesh().face_matrix()))
    return out


def models_case(seed, models):
    rng = np.random.default_rng(seed)
    kind = seed % len(models)
    v, f = models[kind]
    centre, size = v.mean(0), np.ptp(v, 0).max()
    parts = [(v, f)]
    for _ in range(rng.integers(1, 3)):
        mode = rng.integers(0, 3)
        if mode == 0:
            turn, shift = rotation(rng), (rng.random(3) - 0.5) * size * rng.choice([0.0, 0.05, 0.3])
        elif mode == 1:
            a = rng.integers(0, 4, 3) * np.pi / 2
            rx = np.array([[1, 0, 0], [0, np.cos(a[0]), -np.sin(a[0])], [0, np.sin(a[0]), np.cos(a[0])]])
            ry = np.array([[np.cos(a[1]), 0, np.sin(a[1])], [0, 1, 0], [-np.sin(a[1]), 0, np.cos(a[1])]])
            rz = np.array([[np.cos(a[2]), -np.sin(a[2]), 0], [np.sin(a[2]), np.cos(a[2]), 0], [0, 0, 1]])
            turn, shift = rz @ ry @ rx, (rng.random(3) - 0.5) * size * rng.choice([0.0, 0.05, 0.3])
        else:
            turn, shift = np.eye(3), np.round((rng.random(3) - 0.5) * 8) / 16 * size
        parts.append(((v - centre) @ turn.T + centre + shift, f))
    return kind, parts


def check_refused(first, last):
    _, sphere, _ = shapes()
    bad = 0
    for seed in range(first, last):
        at, parts = selfcrossing_case(seed, sphere)
        for sliver in (0.0, 10.0):
            ms = pymeshlab.MeshSet()
            for v, f in parts:
                ms.add_mesh(pymeshlab.Mesh(v, f))
            try:
                ms.generate_surface_intersection_union(bodies=0, sliver_angle=sliver)
                print(f"seed {seed} sliver {sliver}: body {at} was not refused")
                bad += 1
            except pymeshlab.PyMeshLabException as e:
                if f"body {at} " not in str(e) or "intersects itself" not in str(e):
                    print(f"seed {seed} sliver {sliver}: {e}")
                    bad += 1
            if ms.mesh_number() != len(parts):
                print(f"seed {seed} sliver {sliver}: a layer was added")
                bad += 1
    print(f"{last - first} seeds, {bad} failures")
    return 1 if bad else 0


def crossing_faults(ms):
    """Faces with two corners at one place, and faces that really cross another."""
    m = ms.current_mesh()
    v, f = m.vertex_matrix(), m.face_matrix()
    coincident = sum(int(np.all(v[f[:, z]] == v[f[:, (z + 1) % 3]], axis=1).sum()) for z in range(3))
    fresh = pymeshlab.MeshSet()
    fresh.add_mesh(pymeshlab.Mesh(v, f))
    fresh.compute_selection_by_self_intersections_per_face()
    flagged = np.nonzero(fresh.current_mesh().face_selection_array())[0]
    return coincident, len(exactly_intersecting_faces(v, f, flagged))


def sliver_params(seed, drawn):
    """The sliver step's parameters for the seed: the defaults, or drawn at random (--params)."""
    if not drawn:
        return {"sliver_angle": 10.0}, 1.01e-6
    rng = np.random.default_rng(seed + 7_000_003)
    budget = float(10 ** rng.uniform(-9, -3))
    return {"sliver_angle": float(rng.uniform(1, 59)),
            "sliver_max_deviation": float(10 ** rng.uniform(-5, -1)),
            "sliver_max_volume_change": budget}, budget * 1.01 + 1e-12


def far_transform(seed, drawn):
    """(scale, offset) for --transform, or None: a power of two, and an offset of 10-1e5 scales
    whose components are each within a factor two of the coordinates near it."""
    if not drawn:
        return None
    rng = np.random.default_rng(seed + 9_000_011)
    scale = 2.0 ** int(rng.integers(-60, 61))
    offset = scale * 10 ** rng.uniform(1, 5) * rng.uniform(1.5, 2, 3) * rng.choice([-1.0, 1.0], 3)
    return scale, offset


def moved(parts, transform):
    if transform is None:
        return parts
    scale, offset = transform
    return [(v * scale + offset, f) for v, f in parts]


def moved_back(v, transform):
    if transform is None:
        return v
    scale, offset = transform
    return (v - offset) / scale


def main():
    first, last = int(sys.argv[1]), int(sys.argv[2])
    if "--selfcrossing" in sys.argv[3:]:
        return check_refused(first, last)
    nonconvex = "--nonconvex" in sys.argv[3:]
    models = load_models() if "--models" in sys.argv[3:] else None
    drawn = "--params" in sys.argv[3:]
    far = "--transform" in sys.argv[3:]
    cube, sphere, cube2 = shapes()
    ms = pymeshlab.MeshSet()
    ms.create_torus(hradius=0.6, vradius=0.2, hsubdiv=24, vsubdiv=12)
    torus = (ms.current_mesh().vertex_matrix(), ms.current_mesh().face_matrix())
    bad = disagreements = 0
    for seed in range(first, last):
        if models:
            kind, parts = models_case(seed, models)
        elif nonconvex:
            kind, parts = nonconvex_case(seed, sphere, torus)
        else:
            kind, parts = case(seed, cube, sphere, cube2)
        transform = far_transform(seed, far)
        far_parts = moved(parts, transform)
        parts = [(moved_back(v, transform), f) for v, f in far_parts]  # what the union gets, near
        ref = reference(parts)
        params, budget = sliver_params(seed, drawn)
        for sliver, tol in ((0.0, 1e-9), (params["sliver_angle"], budget)):
            ms = pymeshlab.MeshSet()
            for v, f in far_parts:
                ms.add_mesh(pymeshlab.Mesh(v, f))
            try:
                ms.generate_surface_intersection_union(bodies=0, **(params if sliver > 0 else {"sliver_angle": 0.0}))
            except pymeshlab.PyMeshLabException as e:
                print(f"seed {seed} kind {kind} sliver {sliver}: {e}")
                bad += 1
                continue
            if transform is not None:  # measured near the origin, where MeshLab's measures work
                m = ms.current_mesh()
                near = pymeshlab.MeshSet()
                near.add_mesh(pymeshlab.Mesh(moved_back(m.vertex_matrix(), transform), m.face_matrix()))
                ms = near
            topo = ms.get_topological_measures()
            volume = ms.get_geometric_measures().get("mesh_volume", float("nan"))
            err = abs(volume / ref - 1)
            if not err <= tol and topo["is_mesh_two_manifold"] and not topo["boundary_edges"]:
                # manifold3d perturbs coincident geometry symbolically; MeshLab's union
                # (libigl on CGAL's exact kernel) arbitrates.
                exact = meshlab_union_volume(parts)
                if abs(volume / exact - 1) <= tol:
                    print(f"seed {seed} kind {kind} sliver {sliver}: manifold3d's volume differs by "
                          f"{volume / ref - 1:.2e}; MeshLab's exact union agrees ({volume / exact - 1:.1e})")
                    disagreements += 1
                    continue
            if topo["boundary_edges"] or not topo["is_mesh_two_manifold"] or not err <= tol:
                print(f"seed {seed} kind {kind} sliver {sliver}: boundary {topo['boundary_edges']} "
                      f"manifold {topo['is_mesh_two_manifold']} volume error {err:.2e}")
                bad += 1
            elif sliver > 0:
                coincident, crossing = crossing_faults(ms)
                if coincident or crossing:
                    print(f"seed {seed} kind {kind} sliver {sliver}: {coincident} faces with coincident "
                          f"corners, {crossing} crossing faces")
                    bad += 1
    print(f"{last - first} seeds, {bad} failures, {disagreements} where only manifold3d differs")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
