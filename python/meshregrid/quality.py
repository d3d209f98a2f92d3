"""Triangle quality and distance measures for comparing meshes of one surface."""
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


def mesh_quality(ms: pymeshlab.MeshSet, mesh_id: int, reference_id: int = None) -> dict:
    """Angles of layer ``mesh_id`` and, with a reference layer, the symmetric Hausdorff
    distance to it (sampled on faces, as a fraction of the reference's diagonal)."""
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
        kw = dict(samplenum=max(10000, 10 * m.face_number()), sampleface=True, sampleedge=True,
                  samplevert=True, maxdist=pymeshlab.PureValue(diag))
        current = ms.current_mesh_id()
        d = max(ms.get_hausdorff_distance(sampledmesh=mesh_id, targetmesh=reference_id, **kw)["max"],
                ms.get_hausdorff_distance(sampledmesh=reference_id, targetmesh=mesh_id, **kw)["max"])
        ms.set_current_mesh(current)
        out["hausdorff_pct_diag"] = float(100 * d / diag)
    return out
