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
