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


def one_way_hausdorff(ms: pymeshlab.MeshSet, sampled_id: int, target_id: int, samples: int,
                      maxdist: float = None) -> float:
    """Largest distance from points sampled on layer ``sampled_id`` (vertices, edges and
    faces: PyMeshLab's default samples 8 vertices) to layer ``target_id``. Distances beyond
    ``maxdist`` (default: PyMeshLab's 5% of the diagonal) are not measured."""
    kw = dict(sampledmesh=sampled_id, targetmesh=target_id, samplenum=samples, samplevert=True,
              sampleedge=True, sampleface=True)
    if maxdist is not None:
        kw["maxdist"] = pymeshlab.PureValue(maxdist)
    return ms.get_hausdorff_distance(**kw)["max"]


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
        samples = max(10000, 10 * m.face_number())
        current = ms.current_mesh_id()
        d = max(one_way_hausdorff(ms, mesh_id, reference_id, samples, diag),
                one_way_hausdorff(ms, reference_id, mesh_id, samples, diag))
        ms.set_current_mesh(current)
        out["hausdorff_pct_diag"] = float(100 * d / diag)
    return out
