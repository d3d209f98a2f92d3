"""Triangle quality and distance measures for comparing meshes of one surface."""
from fractions import Fraction

import numpy as np
import pymeshlab


def face_angles(vertices: np.ndarray, faces: np.ndarray) -> np.ndarray:
    """All interior angles, in degrees, as an (F, 3) array."""
    p = vertices[faces]
    out = np.empty(faces.shape, float)
    for k in range(3):
        a, b, c = p[:, k], p[:, (k + 1) % 3], p[:, (k + 2) % 3]
        u, v = b - a, c - a
        cos = np.einsum("ij,ij->i", u, v) / np.maximum(np.linalg.norm(u, axis=1) * np.linalg.norm(v, axis=1), 1e-300)
        out[:, k] = np.degrees(np.arccos(np.clip(cos, -1.0, 1.0)))
    return out


def one_way_hausdorff(ms: pymeshlab.MeshSet, sampled_id: int, target_id: int, samples: int,
                      maxdist: float = None) -> float:
    """Largest distance from points sampled on layer ``sampled_id`` (vertices, edges and
    faces: PyMeshLab's default samples 8 vertices) to layer ``target_id``. PyMeshLab drops the
    samples farther than ``maxdist`` from the maximum (its default: half a diagonal), so the
    default here is the diagonal of the box around both layers, which no distance exceeds."""
    if maxdist is None:
        boxes = [ms.mesh(i).bounding_box() for i in (sampled_id, target_id)]
        lo = np.minimum(boxes[0].min(), boxes[1].min())
        hi = np.maximum(boxes[0].max(), boxes[1].max())
        maxdist = float(np.linalg.norm(hi - lo))
    return ms.get_hausdorff_distance(sampledmesh=sampled_id, targetmesh=target_id, samplenum=samples,
                                     samplevert=True, sampleedge=True, sampleface=True,
                                     maxdist=pymeshlab.PureValue(maxdist))["max"]


def hausdorff(ms: pymeshlab.MeshSet, a_id: int, b_id: int, samples: int) -> float:
    """Symmetric Hausdorff distance between layers ``a_id`` and ``b_id``, sampled both ways
    (one_way_hausdorff); the current layer stays the same."""
    current = ms.current_mesh_id()
    d = max(one_way_hausdorff(ms, a_id, b_id, samples), one_way_hausdorff(ms, b_id, a_id, samples))
    ms.set_current_mesh(current)
    return d


def mesh_quality(ms: pymeshlab.MeshSet, mesh_id: int, reference_id: int = None) -> dict:
    """Angles of layer ``mesh_id`` and, with a reference layer, the symmetric Hausdorff
    distance to it (sampled on vertices, edges and faces, in percent of the reference's
    diagonal)."""
    m = ms.mesh(mesh_id)
    angles = face_angles(m.vertex_matrix(), m.face_matrix())
    smallest = angles.min(axis=1)
    out = {
        "faces": int(m.face_number()),
        "vertices": int(m.vertex_number()),
        "min_angle": float(smallest.min()),
        "mean_min_angle": float(smallest.mean()),
        "faces_under_30deg_pct": float(100 * (smallest < 30).mean()),
        "max_angle": float(angles.max()),
    }
    if reference_id is not None:
        diag = ms.mesh(reference_id).bounding_box().diagonal()
        d = hausdorff(ms, mesh_id, reference_id, max(10000, 10 * m.face_number()))
        out["hausdorff_pct_diag"] = float(100 * d / diag)
    return out


def _orient(a, b, c, d):
    u, v, w = [x - y for x, y in zip(b, a)], [x - y for x, y in zip(c, a)], [x - y for x, y in zip(d, a)]
    det = u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0]) + u[2] * (v[0] * w[1] - v[1] * w[0])
    return (det > 0) - (det < 0)


def _orient2(a, b, c, i, j):
    det = (b[i] - a[i]) * (c[j] - a[j]) - (b[j] - a[j]) * (c[i] - a[i])
    return (det > 0) - (det < 0)


def _coplanar_segment_meets_triangle(p, q, tri):
    """Closed segment pq against the closed triangle in its plane, in the projection that
    drops the normal's largest component (one to one on the plane)."""
    a, b, c = tri
    n = [(b[1] - a[1]) * (c[2] - a[2]) - (b[2] - a[2]) * (c[1] - a[1]),
         (b[2] - a[2]) * (c[0] - a[0]) - (b[0] - a[0]) * (c[2] - a[2]),
         (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])]
    k = max(range(3), key=lambda t: abs(n[t]))
    i, j = (k + 1) % 3, (k + 2) % 3
    s = _orient2(a, b, c, i, j)
    if s == 0:
        return True  # a degenerate triangle: counted as a hit
    for x in (p, q):
        if all(s * _orient2(u, w, x, i, j) >= 0 for u, w in ((a, b), (b, c), (c, a))):
            return True

    def on(u, w, x):  # x on the closed segment uw, known collinear
        return all(min(u[m], w[m]) <= x[m] <= max(u[m], w[m]) for m in (i, j))

    for u, w in ((a, b), (b, c), (c, a)):
        o1, o2 = _orient2(p, q, u, i, j), _orient2(p, q, w, i, j)
        o3, o4 = _orient2(u, w, p, i, j), _orient2(u, w, q, i, j)
        if o1 * o2 < 0 and o3 * o4 < 0:
            return True
        if (o1 == 0 and on(p, q, u)) or (o2 == 0 and on(p, q, w)) or (o3 == 0 and on(u, w, p)) or \
           (o4 == 0 and on(u, w, q)):
            return True
    return False


def _segment_meets_triangle(p, q, tri):
    a, b, c = tri
    sp, sq = _orient(a, b, c, p), _orient(a, b, c, q)
    if sp * sq > 0:
        return False
    if sp == 0 and sq == 0:
        return _coplanar_segment_meets_triangle(p, q, tri)
    s = [_orient(p, q, a, b), _orient(p, q, b, c), _orient(p, q, c, a)]
    return all(x >= 0 for x in s) or all(x <= 0 for x in s)


def exactly_intersecting_faces(v: np.ndarray, f: np.ndarray, faces) -> list:
    """Of the given faces, those that meet a face sharing no corner with them, decided with
    exact rationals (to re-check what MeshLab's floating-point selection flags). Corners at
    one place count as shared, as where two sheets touch (MeshLab tells corners apart by
    their vertex only)."""
    _, place = np.unique(v, axis=0, return_inverse=True)
    place = place.reshape(-1)
    lo, hi = v[f].min(1), v[f].max(1)
    out = []
    for i in faces:
        ti = [[Fraction(x) for x in v[k]] for k in f[i]]
        near = np.nonzero(np.all(lo <= hi[i], 1) & np.all(hi >= lo[i], 1))[0]
        for j in near:
            if j == i or set(place[f[i]]) & set(place[f[j]]):
                continue
            tj = [[Fraction(x) for x in v[k]] for k in f[j]]
            if any(_segment_meets_triangle(tj[e], tj[(e + 1) % 3], ti) for e in range(3)) or \
               any(_segment_meets_triangle(ti[e], ti[(e + 1) % 3], tj) for e in range(3)):
                out.append(int(i))
                break
    return out
