"""Honest patch-gap cases made from closed meshes, for the healing tests and
scripts/compare_healing.py: split a closed mesh into patches at its sharp
edges (stage 1's patch_id), give every patch its own copy of the seam
vertices, then damage the seams in one of four ways.

- "duplicate": the copies stay where they were (duplicated seams)
- "gap":       every copy retreats into its own patch by width/2 (a gap about width wide)
- "overlap":   every copy advances past the seam by width/2 (an overlap about width wide)
- "tjunction": even patches get a vertex at the middle of each seam edge (T-junctions)
"""
import numpy as np

KINDS = ("duplicate", "gap", "overlap", "tjunction")


def split_patches(vertices, faces, patch):
    """Each patch gets its own copy of its vertices. Returns (V, F, patch, origin, seam)
    where origin[i] is the input vertex of copy i and seam[i] says the input vertex
    is used by more than one patch."""
    keys = {}
    new_faces = np.empty_like(faces)
    origin = []
    for f, tri in enumerate(faces):
        for k, v in enumerate(tri):
            key = (int(patch[f]), int(v))
            if key not in keys:
                keys[key] = len(origin)
                origin.append(int(v))
            new_faces[f, k] = keys[key]
    origin = np.array(origin)
    patches_per_vertex = np.zeros(len(vertices), dtype=int)
    np.add.at(patches_per_vertex, origin, 1)
    return vertices[origin].copy(), new_faces, np.asarray(patch).copy(), origin, patches_per_vertex[origin] > 1


def _into_patch_directions(vertices, faces, seam):
    """For every seam copy: unit vector from the vertex towards the centroid of its faces."""
    centroid_sum = np.zeros_like(vertices)
    count = np.zeros(len(vertices))
    centroids = vertices[faces].mean(axis=1)
    for k in range(3):
        np.add.at(centroid_sum, faces[:, k], centroids)
        np.add.at(count, faces[:, k], 1)
    d = centroid_sum / np.maximum(count, 1)[:, None] - vertices
    d /= np.maximum(np.linalg.norm(d, axis=1), 1e-300)[:, None]
    d[~seam] = 0
    return d


def _split_seam_edges(vertices, faces, patch, seam, which_patches):
    """Inserts the midpoint of every seam edge of the chosen patches (one-sided re-triangulation)."""
    vertices = list(map(np.array, vertices))
    faces = [list(t) for t in faces]
    patch = list(patch)
    border = {}
    for f, t in enumerate(faces):
        for k in range(3):
            e = tuple(sorted((t[k], t[(k + 1) % 3])))
            border.setdefault(e, []).append(f)
    todo = [e for e, fs in border.items()
            if len(fs) == 1 and seam[e[0]] and seam[e[1]] and patch[fs[0]] in which_patches]
    holder = {e: border[e][0] for e in todo}
    for a, b in todo:
        f = holder[(a, b)]
        t = faces[f]
        k = next(k for k in range(3) if {t[k], t[(k + 1) % 3]} == {a, b})
        u, v, w = t[k], t[(k + 1) % 3], t[(k + 2) % 3]
        m = len(vertices)
        vertices.append((vertices[u] + vertices[v]) / 2)
        faces[f] = [u, m, w]
        faces.append([m, v, w])
        patch.append(patch[f])
        key = tuple(sorted((v, w)))
        if key in holder and holder[key] == f:
            holder[key] = len(faces) - 1
    return np.array(vertices), np.array(faces), np.array(patch)


def make_case(vertices, faces, patch, kind, width=0.0):
    """Returns (V, F, patch) of the damaged patch set."""
    V, F, P, _, seam = split_patches(np.asarray(vertices, float), np.asarray(faces), patch)
    if kind == "duplicate":
        return V, F, P
    if kind in ("gap", "overlap"):
        d = _into_patch_directions(V, F, seam)
        sign = 1.0 if kind == "gap" else -1.0
        return V + sign * d * width / 2, F, P
    if kind == "tjunction":
        even = {p for p in np.unique(P) if p % 2 == 0}
        return _split_seam_edges(V, F, P, seam, even)
    raise ValueError(f"unknown case kind {kind!r}; use one of {KINDS}")


def boundary_edges(faces):
    e = np.sort(np.concatenate([faces[:, [0, 1]], faces[:, [1, 2]], faces[:, [2, 0]]]), axis=1)
    _, counts = np.unique(e, axis=0, return_counts=True)
    return int((counts == 1).sum())


def non_manifold_edges(faces):
    e = np.sort(np.concatenate([faces[:, [0, 1]], faces[:, [1, 2]], faces[:, [2, 0]]]), axis=1)
    _, counts = np.unique(e, axis=0, return_counts=True)
    return int((counts > 2).sum())


def consistently_oriented(faces):
    """No directed edge is used twice (two faces across an edge run it in opposite directions)."""
    d = np.concatenate([faces[:, [0, 1]], faces[:, [1, 2]], faces[:, [2, 0]]])
    _, counts = np.unique(d, axis=0, return_counts=True)
    return bool((counts == 1).all())


def signed_volume(vertices, faces):
    a, b, c = (vertices[faces[:, k]] for k in range(3))
    return float(np.einsum("ij,ij->i", a, np.cross(b, c)).sum() / 6)


def box_of_six_faces(resolutions=(2, 3, 4, 2, 3, 5), offset=0.0):
    """Cube [-1,1]^3 whose six faces are triangulated separately (T-junctions on
    every cube edge when resolutions differ); offset moves each face outward,
    leaving gaps of about offset*sqrt(2) along the cube edges."""
    V, F, P = [], [], []
    for k in range(6):
        axis, side = k % 3, (1.0 if k < 3 else -1.0)
        u, v = (axis + 1) % 3, (axis + 2) % 3
        n = resolutions[k]
        base = len(V)
        for j in range(n + 1):
            for i in range(n + 1):
                p = [0.0, 0.0, 0.0]
                p[axis] = side * (1 + offset)
                p[u] = -1 + 2 * i / n
                p[v] = -1 + 2 * j / n
                V.append(p)
        for j in range(n):
            for i in range(n):
                a = base + j * (n + 1) + i
                t1, t2 = [a, a + 1, a + n + 2], [a, a + n + 2, a + n + 1]
                if side < 0:
                    t1, t2 = t1[::-1], t2[::-1]
                F += [t1, t2]
                P += [k, k]
    return np.array(V), np.array(F), np.array(P)
