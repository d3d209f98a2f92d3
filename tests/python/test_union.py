"""Regression tests of generate_surface_intersection_union through PyMeshLab.

Every union is checked for what the issue asks: closed and two-manifold (PyMeshLab's
topological measures), consistently oriented (positive volume and a single orientation
per edge), no self-intersections (MeshLab's own selection selects 0 faces), and a
volume equal to manifold3d's union of the same bodies.
"""
import math
import pathlib

import numpy as np
import pymeshlab
import pytest

from conftest import assert_unchanged, load, raises_on, shared_mesh, snapshot
from meshregrid.quality import exactly_intersecting_faces, one_way_hausdorff

manifold3d = pytest.importorskip("manifold3d")

LAYERS, COMPONENTS = 0, 1
# Without the sliver step the union is the exact arrangement rounded to doubles.
EXACT_VOLUME_RTOL = 1e-9
# The sliver step changes the volume by at most sliver_max_volume_change (default 1e-6);
# its moves give the volume back, so it is mostly far below that (measured 7e-16 balls,
# 9e-16 rabbit, 4e-15 ten spheres; box.STL -1.0e-6, at the budget).
IMPROVED_VOLUME_RTOL = 1e-6


def reference(meshes):
    """manifold3d's union volume of the given pymeshlab meshes, cavities filled.

    Our filter returns the outer surface (the flood fill starts outside), so voids
    enclosed by the bodies are filled: their shells, which manifold3d keeps as
    components of negative volume, are left out of the reference."""
    parts = []
    for m in meshes:
        mesh = manifold3d.Mesh64(vert_properties=np.ascontiguousarray(m.vertex_matrix(), dtype=np.float64),
                                 tri_verts=np.ascontiguousarray(m.face_matrix(), dtype=np.uint64))
        part = manifold3d.Manifold(mesh)
        assert part.status() == manifold3d.Error.NoError
        parts.append(part)
    union = manifold3d.Manifold.batch_boolean(parts, manifold3d.OpType.Add)
    return sum(v for v in (c.volume() for c in union.decompose()) if v > 0)


def angles(m):
    v, f = m.vertex_matrix(), m.face_matrix()
    out = []
    for z in range(3):
        a, b, c = v[f[:, z]], v[f[:, (z + 1) % 3]], v[f[:, (z + 2) % 3]]
        u, w = b - a, c - a
        out.append(np.degrees(np.arctan2(np.linalg.norm(np.cross(u, w), axis=1), (u * w).sum(1))))
    return np.stack(out, 1)


def self_intersecting_faces(m):
    """Faces MeshLab's self-intersection selection flags that really intersect another face.

    MeshLab's test (vcg::Clean::SelfIntersections) snaps plane distances below an
    absolute 1e-6 to zero, and its result depends on the process's history (it
    flagged two faces 0.03 apart, strictly separated, only after other filters had
    run). Flagged faces are therefore re-checked with exact rational predicates.
    """
    fresh = pymeshlab.MeshSet()
    fresh.add_mesh(pymeshlab.Mesh(m.vertex_matrix(), m.face_matrix()))
    fresh.compute_selection_by_self_intersections_per_face()
    flagged = np.nonzero(fresh.current_mesh().face_selection_array())[0]
    return len(exactly_intersecting_faces(m.vertex_matrix(), m.face_matrix(), flagged))


def check_union(ms, result_id):
    """Closed, manifold, oriented, no self-intersections; returns the volume."""
    ms.set_current_mesh(result_id)
    m = ms.current_mesh()
    topo = ms.get_topological_measures()
    assert topo["boundary_edges"] == 0
    assert topo["is_mesh_two_manifold"]
    assert topo["non_two_manifold_edges"] == 0 and topo["non_two_manifold_vertices"] == 0
    # Consistent orientation: every directed edge exactly once.
    f = m.face_matrix()
    directed = np.concatenate([f[:, [0, 1]], f[:, [1, 2]], f[:, [2, 0]]])
    assert len({tuple(e) for e in directed}) == len(directed)
    assert self_intersecting_faces(m) == 0
    volume = ms.get_geometric_measures()["mesh_volume"]
    assert volume > 0
    return volume


def unite(ms, **kw):
    return ms.generate_surface_intersection_union(**kw)


def multicomponent(name):
    ms = load(f"multicomponent/{name}")
    ms.generate_splitting_by_connected_components()
    parts = [ms.mesh(i) for i in range(1, ms.mesh_number())]
    return ms, parts


@pytest.mark.parametrize("sliver_angle,rtol", [(0.0, EXACT_VOLUME_RTOL), (10.0, IMPROVED_VOLUME_RTOL)])
def test_balls(sliver_angle, rtol):
    ms = load("multicomponent/ballA.off")
    ms.load_new_mesh(str(shared_mesh("multicomponent/ballB.off")))
    ref = reference([ms.mesh(0), ms.mesh(1)])
    r = unite(ms, bodies=LAYERS, sliver_angle=sliver_angle, create_lines_layer=True)
    assert (r["bodies"], r["intersecting_pairs"], r["intersection_lines"]) == (2, 1, 1)
    assert ms.mesh_number() == 4  # inputs, union, lines
    volume = check_union(ms, 2)
    assert volume == pytest.approx(ref, rel=rtol)
    lines = ms.mesh(3)
    assert lines.edge_number() == r["intersection_edges"] and lines.face_number() == 0
    # The intersection edges are the face-edge selection of the result.
    ms.set_current_mesh(2)
    ms.generate_polyline_from_selected_edges()
    assert ms.current_mesh().edge_number() == r["intersection_edges"]


@pytest.mark.parametrize("name", ["box.STL", "rabbit.obj"])
@pytest.mark.parametrize("sliver_angle,rtol", [(0.0, EXACT_VOLUME_RTOL), (10.0, IMPROVED_VOLUME_RTOL)])
def test_shared_multicomponent_meshes(name, sliver_angle, rtol):
    ms, parts = multicomponent(name)
    ref = reference(parts)
    ms.set_current_mesh(0)
    r = unite(ms, bodies=COMPONENTS, sliver_angle=sliver_angle)
    assert r["bodies"] == len(parts)
    assert r["intersecting_pairs"] > 0 and r["intersection_lines"] > 0
    volume = check_union(ms, ms.mesh_number() - 1)
    assert volume == pytest.approx(ref, rel=rtol)


def cube_set(offsets, size=1.0):
    ms = pymeshlab.MeshSet()
    for off in offsets:
        ms.create_cube(size=size)
        ms.compute_matrix_from_translation(axisx=off[0], axisy=off[1], axisz=off[2])
    return ms


@pytest.mark.parametrize("case,offsets,volume", [
    ("shared face", [(0, 0, 0), (1, 0, 0)], 2.0),
    ("shifted by half", [(0, 0, 0), (0.5, 0, 0)], 1.5),
    ("shifted by half diagonally", [(0, 0, 0), (0.5, 0.5, 0.5)], 2 - 0.125),
    ("touching along an edge", [(0, 0, 0), (1, 1, 0)], 2.0),
    ("touching at a corner", [(0, 0, 0), (1, 1, 1)], 2.0),
    ("identical", [(0, 0, 0), (0, 0, 0)], 1.0),
])
def test_degenerate_cube_pairs(case, offsets, volume):
    ms = cube_set(offsets)
    r = unite(ms, bodies=LAYERS)
    assert r["bodies"] == 2
    assert check_union(ms, ms.mesh_number() - 1) == pytest.approx(volume, rel=1e-12), case


def test_enclosed_cavity_is_filled():
    # Six slabs forming the walls of a hollow 3x3x3 box around a 1x1x1 void.
    slabs = [((3, 3, 1), (0, 0, 0)), ((3, 3, 1), (0, 0, 2)), ((3, 1, 3), (0, 0, 0)), ((3, 1, 3), (0, 2, 0)),
             ((1, 3, 3), (0, 0, 0)), ((1, 3, 3), (2, 0, 0))]
    ms = pymeshlab.MeshSet()
    for (sx, sy, sz), (x, y, z) in slabs:
        ms.create_cube(size=1)
        ms.compute_matrix_from_scaling_or_normalization(axisx=sx, axisy=sy, axisz=sz, uniformflag=False)
        ms.compute_matrix_from_translation(axisx=x + sx / 2, axisy=y + sy / 2, axisz=z + sz / 2)
    r = unite(ms, bodies=LAYERS)
    assert r["bodies"] == 6
    assert check_union(ms, 6) == pytest.approx(27.0, rel=1e-12)
    ms.set_current_mesh(6)
    assert ms.get_topological_measures()["connected_components_number"] == 1


def test_sliver_step_reaches_the_input_minimum_angle_on_the_balls():
    # The balls' own triangles have a smallest angle of 5.48 deg; the raw cut has 119
    # faces under 5 deg (down to 0.04 deg). After the default sliver step: none (5.48 deg
    # measured), with the volume within 1e-6 of manifold3d's (test_balls).
    ms = load("multicomponent/ballA.off")
    ms.load_new_mesh(str(shared_mesh("multicomponent/ballB.off")))
    input_min = min(angles(ms.mesh(i)).min() for i in range(2))
    r = unite(ms, bodies=LAYERS)
    out = angles(ms.mesh(2))
    assert (out.min(1) < min(5.0, input_min)).sum() == 0
    assert r["min_angle"] >= min(5.0, input_min) - 1e-9
    assert r["slivers_collapsed"] > 0


def test_sphere_and_identical_copy():
    ms = pymeshlab.MeshSet()
    ms.create_sphere(subdiv=3)
    ms.create_sphere(subdiv=3)
    r = unite(ms, bodies=LAYERS)
    assert r["faces"] == ms.mesh(0).face_number()
    assert check_union(ms, 2) == pytest.approx(ms.get_geometric_measures()["mesh_volume"], rel=1e-12)


def sphere_and_cylinder():
    ms = pymeshlab.MeshSet()
    ms.create_sphere(subdiv=4)
    ms.create_cone(r0=0.4, r1=0.4, h=3, subdiv=64)
    ms.compute_matrix_from_translation(axisx=0.1, axisy=0.05)
    return ms


def test_two_spheres():
    ms = pymeshlab.MeshSet()
    ms.create_sphere(subdiv=4)
    ms.create_sphere(subdiv=4)
    ms.compute_matrix_from_translation(axisx=0.7, axisy=0.2, axisz=0.1)
    ref = reference([ms.mesh(0), ms.mesh(1)])
    r = unite(ms, bodies=LAYERS, sliver_angle=0)
    assert r["intersection_lines"] == 1
    assert check_union(ms, 2) == pytest.approx(ref, rel=EXACT_VOLUME_RTOL)


def test_sphere_and_cylinder_volume_and_lines():
    ms = sphere_and_cylinder()
    ref = reference([ms.mesh(0), ms.mesh(1)])
    r = unite(ms, bodies=LAYERS, sliver_angle=0)
    assert r["intersection_lines"] == 2
    assert check_union(ms, 2) == pytest.approx(ref, rel=EXACT_VOLUME_RTOL)


def test_sliver_step_raises_the_minimum_angle_on_sphere_and_cylinder():
    ms = sphere_and_cylinder()
    input_min = min(angles(ms.mesh(i)).min() for i in range(2))
    raw = unite(ms, bodies=LAYERS, sliver_angle=0)
    ms = sphere_and_cylinder()  # a fresh set: the first union is a visible layer too
    improved = unite(ms, bodies=LAYERS, sliver_angle=10)
    assert improved["slivers_collapsed"] > 0
    assert improved["min_angle"] > raw["min_angle"]
    measured = angles(ms.mesh(2)).min()
    assert measured == pytest.approx(improved["min_angle"], abs=1e-9)
    print(f"input min {input_min:.2f}, raw {raw['min_angle']:.3f}, improved {improved['min_angle']:.3f} deg")


def test_inputs_are_untouched_and_result_is_a_new_layer():
    ms = sphere_and_cylinder()
    before = [snapshot(ms.mesh(i)) for i in range(2)]
    unite(ms, bodies=LAYERS)
    assert ms.mesh_number() == 3 and ms.current_mesh_id() == 2
    for i in range(2):
        assert_unchanged(before[i], ms.mesh(i))


def test_invisible_layers_are_not_bodies():
    ms = cube_set([(0, 0, 0), (0.5, 0, 0), (5, 0, 0)])
    ms.set_mesh_visibility(2, False)
    r = unite(ms, bodies=LAYERS)
    assert r["bodies"] == 2


def test_open_body_is_named_and_nothing_changes():
    ms = pymeshlab.MeshSet()
    ms.create_sphere(subdiv=2)
    ms.create_cube()
    ms.compute_selection_by_condition_per_face(condselect="fi == 0")
    ms.meshing_remove_selected_faces()
    before = [snapshot(ms.mesh(i)) for i in range(2)]
    with raises_on(ms, r"body 1 \(.*\) is not closed"):
        unite(ms, bodies=LAYERS)
    assert ms.mesh_number() == 2
    for i in range(2):
        assert_unchanged(before[i], ms.mesh(i))


def test_non_manifold_body_is_named():
    ms = pymeshlab.MeshSet()
    v = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1], [0, 0, -1], [1, 1, 1]], dtype=float)
    # Tetrahedron plus a fin on edge (0, 1): edge (0, 1) has three faces.
    f = np.array([[0, 2, 1], [0, 1, 3], [1, 2, 3], [0, 3, 2], [0, 1, 5]])
    ms.add_mesh(pymeshlab.Mesh(v, f))
    with raises_on(ms, "non-manifold|not closed"):
        unite(ms, bodies=COMPONENTS)


def test_self_intersecting_body_is_named_and_nothing_changes():
    # A cube with a corner pushed through the opposite face: closed, manifold, oriented,
    # but crossing itself (MeshLab selects its crossing faces too).
    ms = pymeshlab.MeshSet()
    ms.create_cube()
    ms.create_cube()
    v = ms.current_mesh().vertex_matrix().copy()
    corner = np.argmax(v.sum(axis=1))
    v[corner] = [-0.25, -0.25, -1.5]
    ms.add_mesh(pymeshlab.Mesh(v, ms.current_mesh().face_matrix()))
    ms.set_mesh_visibility(1, False)
    ms.compute_selection_by_self_intersections_per_face()
    assert ms.current_mesh().selected_face_number() > 0
    ms.set_selection_none()
    before = [snapshot(ms.mesh(i)) for i in (0, 2)]
    with raises_on(ms, r"body 1 .*intersects itself"):
        unite(ms, bodies=LAYERS)
    assert ms.mesh_number() == 3
    for k, i in enumerate((0, 2)):
        assert_unchanged(before[k], ms.mesh(i))
    # Unchecked (for inputs known to be clean), the result is undefined: here the fill
    # fails with another message, which is what the check is for. The flag is honoured.
    try:
        unite(ms, bodies=LAYERS, check_self_intersections=False)
    except pymeshlab.PyMeshLabException as e:
        assert "intersects itself" not in str(e)


def test_nan_body_is_named():
    ms = pymeshlab.MeshSet()
    ms.create_cube()
    v = ms.current_mesh().vertex_matrix().copy()
    v[3, 1] = np.nan
    ms.add_mesh(pymeshlab.Mesh(v, ms.current_mesh().face_matrix()))
    with raises_on(ms, r"body 1 .*NaN"):
        unite(ms, bodies=LAYERS)


@pytest.mark.parametrize("scale,message", [(1e75, "beyond 1e50"), (1e-100, "smaller than 1e-50"), (1e40, None),
                                           (1e-40, None)])
def test_coordinates_beyond_the_filters_range_are_refused(scale, message):
    # Found in stop 20: the blob and its shifted copy scaled by 1e75 failed with the fill's
    # misleading "coincident faces" message (the filters' products overflow to NaN); scaled
    # by 1e-100 the sliver step silently did nothing. Such scales are now refused by name;
    # within the range the union is the same up to scale.
    v, f = _noisy_blob()
    ms = pymeshlab.MeshSet()
    ms.add_mesh(pymeshlab.Mesh(v * scale, f))
    ms.add_mesh(pymeshlab.Mesh((v + np.array([0.125, 0.0, 0.25])) * scale, f))
    if message:
        before = [snapshot(ms.mesh(i)) for i in (0, 1)]
        with raises_on(ms, r"body 0 .*" + message):
            unite(ms, bodies=LAYERS)
        assert ms.mesh_number() == 2
        for i in (0, 1):
            assert_unchanged(before[i], ms.mesh(i))
        return
    ref = reference([ms.mesh(0), ms.mesh(1)])
    r = unite(ms, bodies=LAYERS)
    topo = ms.get_topological_measures()
    assert topo["boundary_edges"] == 0 and topo["is_mesh_two_manifold"]
    assert ms.get_geometric_measures()["mesh_volume"] == pytest.approx(ref, rel=IMPROVED_VOLUME_RTOL)
    assert r["min_angle"] > 1.0  # the sliver step worked (2.7 degrees at scale 1)


def test_layer_without_faces_is_named():
    ms = pymeshlab.MeshSet()
    ms.create_cube()
    ms.add_mesh(pymeshlab.Mesh(np.random.default_rng(1).random((20, 3))))
    with raises_on(ms, r"body 1 .*empty"):
        unite(ms, bodies=LAYERS)


def test_point_cloud_components_fail_cleanly():
    ms = pymeshlab.MeshSet()
    ms.add_mesh(pymeshlab.Mesh(np.random.default_rng(1).random((20, 3))))
    with raises_on(ms, "no faces"):
        unite(ms, bodies=COMPONENTS)


def test_sphere_cluster():
    rng = np.random.default_rng(7)
    centres = rng.random((30, 3)) * 3
    ms = pymeshlab.MeshSet()
    for c in centres:
        ms.create_sphere(radius=0.5, subdiv=2)
        ms.compute_matrix_from_translation(axisx=c[0], axisy=c[1], axisz=c[2])
    ref = reference([ms.mesh(i) for i in range(len(centres))])
    r = unite(ms, bodies=LAYERS, sliver_angle=0)
    assert r["bodies"] == 30
    assert check_union(ms, ms.mesh_number() - 1) == pytest.approx(ref, rel=EXACT_VOLUME_RTOL)


def test_self_intersection_check_sees_real_intersections():
    ms = cube_set([(0, 0, 0), (0.5, 0.3, 0.2)])
    ms.generate_by_merging_visible_meshes()
    assert self_intersecting_faces(ms.current_mesh()) > 0


def test_pipeline_union_then_regrid_keeps_the_line_and_reaches_30_degrees():
    from meshregrid import pipeline_union
    ms = pymeshlab.MeshSet()
    ms.load_new_mesh(str(shared_mesh("multicomponent/ballA.off")))
    ms.load_new_mesh(str(shared_mesh("multicomponent/ballB.off")))
    r = pipeline_union.union(ms, remesh=True, target_percent=1.0)
    regrid = r["remesh"]
    assert regrid["unmeshed_sides"] == 0
    assert regrid["lines"] >= r["intersection_lines"] == 1
    assert regrid["min_angle"] >= 30.0
    m = ms.current_mesh()
    assert m.face_number() == regrid["faces"]
    assert angles(m).min() >= 30.0
    topo = ms.get_topological_measures()
    assert topo["boundary_edges"] == 0 and topo["is_mesh_two_manifold"]


def _benchmark_cluster(n):
    """benchmark_cluster_parts(n, 3) as one layer per sphere."""
    ms = pymeshlab.MeshSet()
    for v, f in benchmark_cluster_parts(n, 3):
        ms.add_mesh(pymeshlab.Mesh(v, f))
    return ms


def folds_off_lines(ms, union_id, lines_id, degrees=30.0):
    """Edges of the union, off its intersection lines (the lines layer), whose two faces' normals
    differ by more than `degrees`."""
    m = ms.mesh(union_id)
    v, f = m.vertex_matrix(), m.face_matrix()
    at = {tuple(p): i for i, p in enumerate(v)}
    lines = ms.mesh(lines_id)
    lv = lines.vertex_matrix()
    on_line = {frozenset((at[tuple(lv[a])], at[tuple(lv[b])])) for a, b in lines.edge_matrix()}
    n = np.cross(v[f[:, 1]] - v[f[:, 0]], v[f[:, 2]] - v[f[:, 0]])
    n /= np.linalg.norm(n, axis=1)[:, None]
    faces_at = {}
    for i, t in enumerate(f):
        for z in range(3):
            faces_at.setdefault(frozenset((int(t[z]), int(t[(z + 1) % 3]))), []).append(i)
    cos = math.cos(math.radians(degrees))
    return sum(1 for e, fs in faces_at.items() if e not in on_line and len(fs) == 2 and n[fs[0]] @ n[fs[1]] < cos)


def test_sliver_step_folds_no_edge_beside_the_lines_of_the_ten_sphere_cluster():
    # Moves of the sliver step that fold two faces off the lines by more than 30 degrees are
    # refused (unless a collapse removes a face under a degree): before, repeated collapses and
    # relocations beside the cluster's lines left 10 such edges, which the regrid took for ridges
    # (18 corners, 28 lines, 11.8 degrees). The exact arrangement has none either.
    for sliver_angle in (0.0, 10.0):
        ms = _benchmark_cluster(10)
        r = unite(ms, bodies=LAYERS, sliver_angle=sliver_angle, create_lines_layer=True)
        if sliver_angle > 0:
            assert r["slivers_left"] == 0 and r["min_angle"] >= 10.0
        assert folds_off_lines(ms, 10, 11) == 0


def test_pipeline_regrid_of_the_stepped_ten_sphere_cluster_reaches_30_degrees():
    # With no folds beside its lines the stepped union regrids like the exact one: 4 corners,
    # 10 lines, 31.21 degrees (the exact union's 31.32 was needed before), so the pipeline
    # keeps it without the second regrid.
    from meshregrid import pipeline_union
    ms = _benchmark_cluster(10)
    r = pipeline_union.union(ms, remesh=True, target_percent=1.0, regrid_exact_union_too=False)
    regrid = r["remesh"]
    assert not regrid["from_exact_union"]
    assert (regrid["corners"], regrid["lines"], regrid["unmeshed_sides"]) == (4, 10, 0)
    assert regrid["min_angle"] >= 30.0 and angles(ms.current_mesh()).min() >= 30.0
    assert ms.current_mesh_id() == r["remesh_layer"]
    topo = ms.get_topological_measures()
    assert topo["boundary_edges"] == 0 and topo["is_mesh_two_manifold"]
    # The layers: the ten bodies, the union, the regrid, all visible.
    layers = [i for i in range(r["remesh_layer"] + 1) if ms.mesh_id_exists(i)]
    assert len(layers) == 12 and layers[10:] == [r["union_layer"], r["remesh_layer"]]
    assert all(ms.is_mesh_visible(i) for i in layers)


def test_pipeline_regrid_of_the_ten_sphere_cluster_reaches_30_degrees_at_2_percent():
    # Four faces of 22.9-26.5 degrees lay between two lines 0.04 apart, all their corners on the
    # lines: line points slid only where a face around them was under 20 degrees. Under 25
    # they slide there too. Measured: 31.2 degrees (22.9 before).
    from meshregrid import pipeline_union
    ms = _benchmark_cluster(10)
    r = pipeline_union.union(ms, remesh=True, target_percent=2.0)
    assert r["remesh"]["unmeshed_sides"] == 0
    assert angles(ms.current_mesh()).min() >= 30.0
    topo = ms.get_topological_measures()
    assert topo["boundary_edges"] == 0 and topo["is_mesh_two_manifold"]


def _sphere_with_two_nearly_touching_circles(gap):
    """Sphere A (radius 0.5) and two more, B and C, 0.8 from its centre: their intersection
    circles on A (angular radius acos(0.8)) pass `gap` radians apart, a neck of A 0.5 x gap wide
    between them."""
    half = math.acos(0.8) + gap / 2
    ms = pymeshlab.MeshSet()
    for d in ((0.0, 0.0), (math.cos(half), math.sin(half)), (math.cos(half), -math.sin(half))):
        sphere = pymeshlab.MeshSet()
        sphere.create_sphere(radius=0.5, subdiv=4)
        v = sphere.current_mesh().vertex_matrix() + 0.8 * np.array([d[0], d[1], 0.0])
        ms.add_mesh(pymeshlab.Mesh(v, sphere.current_mesh().face_matrix()))
    return ms


def test_pipeline_regrid_meshes_the_neck_between_two_nearly_touching_circles():
    # The neck is 0.002 wide, a twentieth of the 2% target: one row of faces across it had
    # 7.9 degrees. Line points closer than 0.15 x target to another line cap the size at 1.7 x
    # their distance (neck_caps.h). Measured: 30.2 degrees, 26 faces more (of 6,100).
    from meshregrid import pipeline_union
    ms = _sphere_with_two_nearly_touching_circles(0.004)
    r = pipeline_union.union(ms, remesh=True, target_percent=2.0)["remesh"]
    assert r["neck_points"] > 0 and r["unmeshed_sides"] == 0
    assert angles(ms.current_mesh()).min() >= 25.0
    topo = ms.get_topological_measures()
    assert topo["boundary_edges"] == 0 and topo["is_mesh_two_manifold"]


def test_pipeline_regrid_caps_a_wider_neck_between_intersection_lines():
    # Circles 0.016 apart: a neck 0.008 wide, 0.15 x the 2% target and 0.29 x the 1% one, beyond
    # the 0.15 x target reach between lines found by their dihedral angle. Between two lines the
    # caller gave (the union's intersection lines, kept as selected edges) the caps reach 0.45 x
    # target in runs of five points (neck_caps.cpp). Measured (stop 55): at 2% 14.36 -> 30.38
    # degrees, at 1% 25.88 -> 31.19, 42 and 64 faces more.
    from meshregrid import pipeline_union
    for percent in (1.0, 2.0):
        ms = _sphere_with_two_nearly_touching_circles(0.016)
        r = pipeline_union.union(ms, remesh=True, target_percent=percent)["remesh"]
        assert r["neck_points"] > 0 and r["unmeshed_sides"] == 0
        assert angles(ms.current_mesh()).min() >= 30.0, percent
        topo = ms.get_topological_measures()
        assert topo["boundary_edges"] == 0 and topo["is_mesh_two_manifold"]


def test_fifty_sphere_cluster_regrid_keeps_its_necks_over_20_degrees():
    # Sphere clusters have necks wherever two spheres' circles on a third nearly touch: at 1%
    # the 50-sphere benchmark cluster's regrid had 9.0 degrees there; with the neck caps 20.8
    # (126 faces more of 43,000).
    from meshregrid import pipeline_union
    ms = _benchmark_cluster(50)
    r = pipeline_union.union(ms, remesh=True, target_percent=1.0)["remesh"]
    assert r["neck_points"] > 0 and r["unmeshed_sides"] == 0
    assert r["min_angle"] >= 20.0
    topo = ms.get_topological_measures()
    assert topo["boundary_edges"] == 0 and topo["is_mesh_two_manifold"]


def test_fifty_sphere_cluster_regrid_with_relaxed_wedges_reaches_30_degrees():
    # With relax_wedges the cluster's eight triple-point wedges go and what is left is the mesh's:
    # where two intersection lines diverge from a neck their points faced each other across the
    # strip between them (25.5 and 27.3 degrees). Line points there take the largest gain short of
    # 30 degrees, alone or in a pair (line_sliding.h): 29.56 at 1% and 29.29 at 2% (stop 56), the
    # faces around balanced so that any single move made a neighbour worse. Moving the points
    # around such a face together (joint_polish.h, stop 59) lifts them: 30.03 and 30.04 degrees.
    from meshregrid import pipeline_union
    for percent in (1.0, 2.0):
        ms = _benchmark_cluster(50)
        r = pipeline_union.union(ms, remesh=True, target_percent=percent, relax_wedges=True)["remesh"]
        assert r["unmeshed_sides"] == 0 and r["wedge_tips"] == 0
        assert r["jointly_moved"] > 0
        a = angles(ms.current_mesh()).min(1)  # each face's smallest angle
        assert a.min() >= 30.0, percent
        topo = ms.get_topological_measures()
        assert topo["boundary_edges"] == 0 and topo["is_mesh_two_manifold"]


def test_two_hundred_sphere_cluster_regrid_refines_the_narrowest_necks():
    # Between two intersection lines the neck caps go down to 0.01 x target (neck_caps.cpp): at
    # 0.05 x target, strips under 0.03 x target wide between two circles kept faces of the floor's
    # spacing. Measured (stop 57) at 2%: 13.31 -> 14.34 degrees, with relax_wedges 13.31 -> 19.23
    # (246 faces more of 20,000).
    from meshregrid import pipeline_union
    ms = _benchmark_cluster(200)
    r = pipeline_union.union(ms, remesh=True, target_percent=2.0, relax_wedges=True)["remesh"]
    assert r["neck_points"] > 0 and r["unmeshed_sides"] == 0
    assert r["min_angle"] >= 19.0
    topo = ms.get_topological_measures()
    assert topo["boundary_edges"] == 0 and topo["is_mesh_two_manifold"]


def test_union_then_regrid_gives_the_same_meshes_twice():
    # The union's sliver step lends its crossing checks to a second thread and the pipeline
    # regrids two unions; neither may make the output depend on the run. The 50-sphere cluster
    # at 2% with relax_wedges passes through every step: slivers, neck caps, wedges and the
    # exact union's regrid (kept here).
    from meshregrid import pipeline_union
    runs = []
    for _ in range(2):
        ms = _benchmark_cluster(50)
        r = pipeline_union.union(ms, remesh=True, target_percent=2.0, relax_wedges=True)
        assert r["slivers_collapsed"] > 0 and r["remesh"]["neck_points"] > 0 and r["remesh"]["from_exact_union"]
        runs.append([(ms.mesh(i).vertex_matrix().copy(), ms.mesh(i).face_matrix().copy())
                     for i in (r["union_layer"], r["remesh_layer"])])
    for (v0, f0), (v1, f1) in zip(*runs):
        assert np.array_equal(v0, v1) and np.array_equal(f0, f1)


def grid_box(lo, hi, n):
    """Closed box [lo, hi], each side an n x n grid of squares cut in two, outward."""
    lo, hi = np.asarray(lo, float), np.asarray(hi, float)
    points, faces = [], []
    for axis in range(3):
        u, v = (axis + 1) % 3, (axis + 2) % 3
        for top in (False, True):
            base = len(points)
            for i in range(n + 1):
                for j in range(n + 1):
                    p = lo.copy()
                    p[axis] = hi[axis] if top else lo[axis]
                    p[u] += (hi[u] - lo[u]) * i / n
                    p[v] += (hi[v] - lo[v]) * j / n
                    points.append(p)
            for i in range(n):
                for j in range(n):
                    a, b = base + i * (n + 1) + j, base + (i + 1) * (n + 1) + j
                    quad = [(a, b, b + 1), (a, b + 1, a + 1)] if top else [(a, b + 1, b), (a, a + 1, b + 1)]
                    faces += quad
    ms = pymeshlab.MeshSet()
    ms.add_mesh(pymeshlab.Mesh(np.array(points), np.array(faces)))
    ms.meshing_remove_duplicate_vertices()
    return pymeshlab.Mesh(ms.current_mesh().vertex_matrix(), ms.current_mesh().face_matrix())


def test_pipeline_regrid_meshes_a_thin_ledge_between_united_blocks_at_30_degrees():
    # A block with a second one standing on it 0.001 in from its left side (0.05 x the 1% target):
    # the ledge between the block's edge and the intersection line is meshed with elements about
    # as long as it is wide (thin-step caps). Before, its one layer of faces had 4.8 degrees.
    # The blocks' front and back sides are coplanar: there the seam where the second block's side
    # begins runs 0.001 beside the first one's edge, a strip capped the same way (4.5 degrees
    # before, 17.6 now; the rest is the corners at the strips' ends).
    from meshregrid import pipeline_union
    width = 0.001
    ms = pymeshlab.MeshSet()
    ms.add_mesh(grid_box((0, 0, 0), (1, 1, 1), 16))
    ms.add_mesh(grid_box((width, 0, 0.5), (1, 1, 1.5), 16))
    r = pipeline_union.union(ms, remesh=True, target_percent=1.0)
    regrid = r["remesh"]
    assert regrid["thin_step_faces"] > 0 and regrid["unmeshed_sides"] == 0
    m = ms.current_mesh()
    v, f = m.vertex_matrix(), m.face_matrix()
    topo = ms.get_topological_measures()
    assert topo["boundary_edges"] == 0 and topo["is_mesh_two_manifold"]
    # Faces with a corner on the ledge (z = 1, 0 <= x <= width), away from its two ends.
    on_ledge = (np.abs(v[:, 2] - 1) < 1e-9) & (v[:, 0] <= width + 1e-9) & (v[:, 1] > 0.05) & (v[:, 1] < 0.95)
    near = np.any(on_ledge[f], axis=1)
    assert near.sum() > 1000  # points about 1.7 x width apart along both lines
    ledge = pymeshlab.Mesh(v, f[near])
    assert angles(ledge).min() >= 30.0
    assert angles(m).min() >= 17.0


def axis_turn(quarters):
    """Rotation by quarter turns about x, then y, then z (as the union fuzz composes them)."""
    a = np.asarray(quarters) * np.pi / 2
    rx = np.array([[1, 0, 0], [0, np.cos(a[0]), -np.sin(a[0])], [0, np.sin(a[0]), np.cos(a[0])]])
    ry = np.array([[np.cos(a[1]), 0, np.sin(a[1])], [0, 1, 0], [-np.sin(a[1]), 0, np.cos(a[1])]])
    rz = np.array([[np.cos(a[2]), -np.sin(a[2]), 0], [np.sin(a[2]), np.cos(a[2]), 0], [0, 0, 1]])
    return rz @ ry @ rx


def joint_and_two_copies(grid_shift, quarters, turned_random, turned_scale):
    """joint.off with a copy shifted by grid_shift x its size and one turned by quarter turns
    and shifted by (turned_random - 0.5) x its size x turned_scale, built in the same order of
    operations as scripts/fuzz_union.py --models (the cases are bit-exact)."""
    src = load("cad/joint.off")
    base = src.current_mesh()
    v, f = base.vertex_matrix(), base.face_matrix()
    centre, size = v.mean(0), np.ptp(v, 0).max()
    ms = pymeshlab.MeshSet()
    ms.add_mesh(pymeshlab.Mesh(v, f))
    ms.add_mesh(pymeshlab.Mesh((v - centre) @ np.eye(3).T + centre + np.array(grid_shift) * size, f))
    shift = (np.array(turned_random) - 0.5) * size * turned_scale
    ms.add_mesh(pymeshlab.Mesh((v - centre) @ axis_turn(quarters).T + centre + shift, f))
    return ms


def regrid_is_closed_and_two_manifold(ms, percent):
    """Union the layers of `ms` and regrid at `percent` (the pipeline), asserting the regrid is
    complete, closed and two-manifold."""
    from meshregrid import pipeline_union
    regrid = pipeline_union.union(ms, remesh=True, target_percent=percent)["remesh"]
    assert regrid["unmeshed_sides"] == 0 and regrid["non_manifold_points"] == 0
    topo = ms.get_topological_measures()
    assert topo["boundary_edges"] == 0 and topo["is_mesh_two_manifold"]
    assert topo["non_two_manifold_vertices"] == 0


def test_pipeline_regrid_of_joint_with_a_shifted_and_a_turned_copy_is_closed_and_two_manifold():
    # scripts/fuzz_union.py --models, seed 40: joint.off with a shifted copy and a copy turned by
    # quarter turns. The regrid of the stepped union pinched two corners and a line point (a
    # patch's front took a corner or line point from outside the patch's angle there and closed
    # a fan all round it), the exact union's regrid left 25 sides open, and the pipeline kept
    # that open one. The fronts now take such points only within the angle still to mesh.
    ms = joint_and_two_copies([0.125, 0.25, -0.25], [2, 0, 3],
                              [0.47568317752097466, 0.3383906909861234, 0.6018828052702476], 0.3)
    regrid_is_closed_and_two_manifold(ms, 1.0)


def test_pipeline_regrid_of_joint_with_two_copies_has_no_flat_face():
    # scripts/fuzz_union.py --models, seed 72. A loop the front left (four points, one of them
    # on the line between two others) was closed by ear clipping whose only free diagonal ran
    # through that point: a face with its three corners on one line (smallest angle 1e-13
    # degrees). Such a loop now gets a point inside and a fan. Measured 0.37 degrees, a corner
    # beside a line 0.0001 of the diagonal away.
    ms = joint_and_two_copies([-0.25, -0.125, -0.1875], [2, 2, 1],
                              [0.573307837688134, 0.05189084257269705, 0.2913169191596523], 0.0)
    regrid_is_closed_and_two_manifold(ms, 1.0)
    assert angles(ms.current_mesh()).min() > 0.1


def test_pipeline_regrid_at_2_percent_closes_a_long_strip_between_two_close_lines():
    # scripts/fuzz_union.py --models, seed 84, at 2%: a strip 0.00014 wide and 0.6 long between
    # two intersection lines (one input vertex off the lines, so no thin patch) stayed open with
    # 31 sides in the stepped union's regrid and 34 in the exact one's: loops of more than 16
    # sides were left open. A loop of line points only, that thin, is now zipped like a thin
    # patch.
    ms = joint_and_two_copies([0.1875, 0.125, 0.1875], [0, 1, 2],
                              [0.6487956520829201, 0.2828522375542264, 0.282879721819282], 0.0)
    regrid_is_closed_and_two_manifold(ms, 2.0)


def test_pipeline_keeps_the_first_regrid_when_the_second_try_fails(monkeypatch):
    # A refusal in the second try (here forced) must not lose the first regrid: it stays, and
    # the layers the try made go.
    from meshregrid import pipeline_union
    united = pymeshlab.MeshSet.generate_surface_intersection_union

    def exact_union_refused(ms, *args, **kwargs):
        if kwargs.get("sliver_angle") == 0.0:
            united(ms, *args, **kwargs)  # a layer is made, then the refusal
            raise pymeshlab.PyMeshLabException("refused for the test")
        return united(ms, *args, **kwargs)

    monkeypatch.setattr(pymeshlab.MeshSet, "generate_surface_intersection_union", exact_union_refused)
    ms = _benchmark_cluster(10)
    r = pipeline_union.union(ms, remesh=True, target_percent=2.0)
    assert not r["remesh"]["from_exact_union"] and r["remesh"]["unmeshed_sides"] == 0
    layers = [i for i in range(r["remesh_layer"] + 3) if ms.mesh_id_exists(i)]
    assert len(layers) == 12 and layers[10:] == [r["union_layer"], r["remesh_layer"]]
    assert ms.current_mesh_id() == r["remesh_layer"]
    assert all(ms.is_mesh_visible(i) for i in layers)


@pytest.mark.parametrize("target_percent", [0.5, 1.0, 2.0])
def test_pipeline_regrid_of_rabbit_obj_has_no_wedge_the_sliver_step_folded(target_percent):
    # rabbit.obj's stepped union regridded. Its smallest wedge between two lines was 12.29
    # degrees, at a corner the sliver step made at (0.238, 1.42, 0.885): relocations, six in a
    # row, walked a vertex 0.046 across a curved star beside a line and folded two edges by 54
    # and 58 degrees, which the regrid kept as ridges. Moves that fold the surface off the
    # lines now wait for a last round (folds_more): the wedge is gone, and the smallest is
    # 26.33 degrees, where an intersection line meets a crease of the input at
    # (-0.75, 0.39, -0.12). Off the wedges: 30.00, 30.30 and 22.11 degrees at 0.5, 1 and 2%
    # (30.05, 30.30, 24.32 before); at 2% the smallest face sat at an ear tip far from any
    # line, between two corners of the input 0.03 apart (a quarter of the target). Since stop 49
    # the ears' narrow rims cap the size (narrow_rim_faces) and line points follow the size
    # within an input edge: 28.95 at 2%, the wedge the smallest angle at every size. Since stop
    # 50 line points also take small steps and slide in pairs (line_sliding.h): the faces at the
    # two 98-degree corners below the ears, whose first segments were too long for them, pass 30
    # (30.42 at 2%), so every face off the wedges has 30 degrees at all three sizes.
    from meshregrid import pipeline_union
    ms, _ = multicomponent("rabbit.obj")
    ms.set_current_mesh(0)
    r = pipeline_union.union(ms, bodies="components", remesh=True, target_percent=target_percent,
                             regrid_exact_union_too=False)
    regrid = r["remesh"]
    assert regrid["unmeshed_sides"] == 0 and not regrid["from_exact_union"]
    assert regrid["wedge_tips"] >= 1 and regrid["min_wedge_angle"] == pytest.approx(26.33, abs=0.01)
    assert regrid["min_angle_off_wedges"] >= 30.0
    assert angles(ms.current_mesh()).min() >= 26.3
    if target_percent == 2.0:
        assert regrid["narrow_rim_faces"] > 0
    topo = ms.get_topological_measures()
    assert topo["boundary_edges"] == 0 and topo["is_mesh_two_manifold"]


def box_and_turned_slab(alpha_deg):
    """Box [0,2]x[0,2]x[0,1] and a slab whose face through (1, 0) is turned by ``alpha_deg`` from
    the box's front top edge: the box's top keeps a wedge of that angle between the edge and the
    intersection line."""
    ms = pymeshlab.MeshSet()
    ms.create_cube(size=1.0)
    unit, faces = ms.current_mesh().vertex_matrix() + 0.5, ms.current_mesh().face_matrix()
    a = np.radians(alpha_deg)
    slab = unit * [6.0, 4.0, 1.5] + [-3.0, 0.0, 0.5]  # (along the face, away from it, z)
    xy = np.array([1.0, 0.0]) + np.outer(slab[:, 0], [np.cos(a), np.sin(a)]) + np.outer(slab[:, 1], [-np.sin(a), np.cos(a)])
    out = pymeshlab.MeshSet()
    out.add_mesh(pymeshlab.Mesh(unit * [2.0, 2.0, 1.0], faces))
    out.add_mesh(pymeshlab.Mesh(np.c_[xy, slab[:, 2]], faces))
    return out


@pytest.mark.parametrize("alpha", [15.0, 20.0])
def test_pipeline_relax_wedges_lets_a_line_and_a_crease_share_their_first_segment(alpha):
    # Kept apart, the intersection line and the box's edge leave their meeting points at alpha:
    # two wedge tips of exactly alpha. Relaxed, their first points merge halfway and the next
    # faces between them see about twice the angle: at 1% every face reaches 30 degrees
    # (measured 30.02 and 30.47), and the regrid and the union stay within 0.25 and 0.17 x the
    # size of each other (the lines' detour at the tips; 0.19 and 0.14 the other way). Bound: 0.3,
    # half the 0.6 x size the merged points may be apart, which a merge halfway moves each line.
    from meshregrid import pipeline_union
    kept = box_and_turned_slab(alpha)
    plain = pipeline_union.union(kept, remesh=True, target_percent=1.0)["remesh"]
    assert plain["wedge_tips"] >= 1 and plain["min_wedge_angle"] == pytest.approx(alpha, abs=1e-6)
    ms = box_and_turned_slab(alpha)
    r = pipeline_union.union(ms, remesh=True, target_percent=1.0, relax_wedges=True)
    relaxed = r["remesh"]
    assert relaxed["relaxed_wedges"] >= 2 and relaxed["wedge_tips"] == 0
    assert relaxed["min_angle"] >= 30.0 and angles(ms.current_mesh()).min() >= 30.0
    assert relaxed["unmeshed_sides"] == 0 and relaxed["missing_feature_edges"] == 0
    topo = ms.get_topological_measures()
    assert topo["boundary_edges"] == 0 and topo["is_mesh_two_manifold"]
    far = one_way_hausdorff(ms, r["union_layer"], r["remesh_layer"], 200000)
    back = one_way_hausdorff(ms, r["remesh_layer"], r["union_layer"], 200000)
    assert max(far, back) <= 0.3 * relaxed["target_length"]


@pytest.mark.parametrize("target_percent", [1.0, 2.0])
def test_pipeline_relax_wedges_takes_rabbit_obj_to_30_degrees_everywhere(target_percent):
    # rabbit.obj's one wedge (26.33 degrees, an intersection line meeting a crease of the input)
    # is relaxed: every face of the regrid has 30 degrees (measured 30.30 and 30.42), and the
    # distance to the union (hausdorff_rel) stays as it was, 0.005 and 0.010 of the diagonal.
    from meshregrid import pipeline_union
    ms, _ = multicomponent("rabbit.obj")
    ms.set_current_mesh(0)
    r = pipeline_union.union(ms, bodies="components", remesh=True, target_percent=target_percent,
                             regrid_exact_union_too=False, relax_wedges=True)
    regrid = r["remesh"]
    assert regrid["unmeshed_sides"] == 0 and regrid["relaxed_wedges"] >= 1 and regrid["wedge_tips"] == 0
    assert regrid["min_angle"] >= 30.0 and angles(ms.current_mesh()).min() >= 30.0
    assert regrid["hausdorff_rel"] <= 0.0055 * target_percent
    topo = ms.get_topological_measures()
    assert topo["boundary_edges"] == 0 and topo["is_mesh_two_manifold"]


def test_pipeline_relax_wedges_merges_beside_a_junction_of_lines():
    # scripts/fuzz_union.py --models, seed 17 (cad/part.off with copies) at 1%: a wedge tip
    # beside a point that two lines run through (not a corner) was not relaxed, as shared points
    # were left alone: 19.88 degrees. Such a junction now takes the other point and stays where it
    # is: measured 30.03 everywhere (stop 60; over seeds 0-95, 13 regrids better, none worse).
    from meshregrid import pipeline_union
    ms = _models_case_layers(17)
    r = pipeline_union.union(ms, remesh=True, target_percent=1.0, relax_wedges=True)["remesh"]
    assert r["relaxed_wedges"] > 0 and r["unmeshed_sides"] == 0
    assert r["min_angle"] >= 30.0 and angles(ms.current_mesh()).min() >= 30.0
    topo = ms.get_topological_measures()
    assert topo["boundary_edges"] == 0 and topo["is_mesh_two_manifold"]


def test_pipeline_relax_wedges_makes_lines_that_pass_close_meet():
    # scripts/fuzz_union.py --models, seed 34 (cad/fandisk.obj with copies) at 1%: two feature
    # lines pass closer than a quarter of the size without meeting, and the faces between them
    # stayed at 5.78 degrees. The lines now meet there (close_line_gaps, stop 61): measured 20.00
    # (deterministic; half a degree below it).
    from meshregrid import pipeline_union
    ms = _models_case_layers(34)
    r = pipeline_union.union(ms, remesh=True, target_percent=1.0, relax_wedges=True)["remesh"]
    assert r["closed_line_gaps"] > 0 and r["unmeshed_sides"] == 0
    assert r["min_angle"] >= 19.5 and angles(ms.current_mesh()).min() >= 19.5
    topo = ms.get_topological_measures()
    assert topo["boundary_edges"] == 0 and topo["is_mesh_two_manifold"]


def test_pipeline_breaks_a_tie_at_a_shared_wedge_by_the_angles_off_the_wedges():
    # fuzz_union --models seed 32 at 1%: both regrids keep the same 7.0144250828-degree wedge;
    # the exact union's won by 1e-14 of a degree with a face of 7.72 degrees off the wedges,
    # against 20.31 in the stepped union's regrid.
    from meshregrid.pipeline_union import _better
    stepped, exact = (True, 7.014425082836387, 20.31), (True, 7.014425082836374 + 2e-14, 7.72)
    assert not _better(exact, stepped) and _better(stepped, exact)
    # Otherwise the smallest angle decides, and before it a complete, closed regrid.
    assert _better((True, 7.02, 7.72), stepped)
    assert not _better((True, 7.0, 30.0), stepped)
    assert _better((True, 1.0, 1.0), (False, 30.0, 30.0))


def test_pipeline_keeps_the_stepped_regrid_where_the_exact_unions_needles_do_worse():
    # box.STL: the exact arrangement's needles regrid to a face of 0.0 degrees; the stepped
    # union's regrid (0.97, bounded by plate corners 0.002 apart) stays.
    from meshregrid import pipeline_union
    ms = load("multicomponent/box.STL")
    r = pipeline_union.union(ms, bodies="components", remesh=True, target_percent=2.0)
    assert not r["remesh"]["from_exact_union"]
    assert r["remesh"]["min_angle"] > 0.5
    layers = [i for i in range(r["remesh_layer"] + 1) if ms.mesh_id_exists(i)]
    assert layers == [0, r["union_layer"], r["remesh_layer"]]


@pytest.mark.parametrize("target_percent", [1.0, 2.0])
def test_pipeline_union_then_regrid_reaches_30_degrees_on_sphere_and_cylinder(target_percent):
    # The quality case (its peers leave 2-27% of faces under 5 degrees there): the
    # union regridded with the intersection lines and the cylinder's rims as ridges.
    from meshregrid import pipeline_union
    ms = sphere_and_cylinder()
    r = pipeline_union.union(ms, remesh=True, target_percent=target_percent)
    regrid = r["remesh"]
    assert regrid["unmeshed_sides"] == 0
    assert regrid["lines"] >= r["intersection_lines"] == 2
    assert angles(ms.current_mesh()).min() >= 30.0
    topo = ms.get_topological_measures()
    assert topo["boundary_edges"] == 0 and topo["is_mesh_two_manifold"]


def test_box_union_regridded_with_the_filters_defaults_is_closed():
    # box.STL's plates nearly line up: the union leaves needles 0.14 long at the plates'
    # corners, each a sliver patch bordered by a fold. The noise suppression (min_line_length,
    # 2 x target by default) merged them into their neighbours across the fold, which the
    # front cannot cross: 19 patches stayed open (43 boundary edges). The remesher now meshes
    # a second time keeping them. Geometry bounds the angles here (plate corners 0.002 apart).
    ms = load("multicomponent/box.STL")
    unite(ms, bodies=COMPONENTS)
    r = ms.meshing_advancing_front_remesh(target_length=pymeshlab.PercentageValue(1.0),
                                          use_selected_edges_as_ridges=True)
    assert r["unmeshed_sides"] == 0 and r["unmeshed_patches"] == 0
    assert r["kept_folded_slivers"]
    topo = ms.get_topological_measures()
    assert topo["boundary_edges"] == 0 and topo["is_mesh_two_manifold"]


def test_box_union_regridded_by_the_pipeline_is_closed_at_2_percent():
    # At 2% the pipeline (min_line_length = target) left 2 patches open, 9 boundary edges.
    from meshregrid import pipeline_union
    ms = load("multicomponent/box.STL")
    r = pipeline_union.union(ms, bodies="components", remesh=True, target_percent=2.0)
    regrid = r["remesh"]
    assert regrid["unmeshed_sides"] == 0
    topo = ms.get_topological_measures()
    assert topo["boundary_edges"] == 0 and topo["is_mesh_two_manifold"]


def test_box_union_of_its_plates_as_layers_regridded_at_1_percent_is_two_manifold():
    # The plates as layers (merged vertices, one layer each) give a patch that folds back over
    # itself; its front closed one triangle from both sides. The two faces, facing apart,
    # pinched two corners and a line point (2 non-manifold vertices). The remesher removed
    # such pairs (stop 37, tests/cpp/remesh/test_flat_pockets.cpp); since stop 45 the second
    # face is not made here at all (a front takes a line or corner point only within the angle
    # still to mesh there), so no pair is left to remove.
    src = load("multicomponent/box.STL")
    src.meshing_remove_duplicate_vertices()
    src.generate_splitting_by_connected_components()
    ms = pymeshlab.MeshSet()
    for i in range(1, src.mesh_number()):
        ms.add_mesh(pymeshlab.Mesh(src.mesh(i).vertex_matrix(), src.mesh(i).face_matrix()))
    regrid_is_closed_and_two_manifold(ms, 1.0)


def test_cli_union_writes_union_and_lines(tmp_path):
    import json
    import subprocess
    import sys
    out, lines = tmp_path / "u.ply", tmp_path / "l.obj"
    a = shared_mesh("multicomponent/ballA.off")
    b = shared_mesh("multicomponent/ballB.off")
    proc = subprocess.run([sys.executable, "-m", "meshregrid", "union", str(a), str(b), str(out), "--lines", str(lines)],
                          capture_output=True, text=True, check=True)
    result = json.loads(proc.stdout)
    assert result["bodies"] == 2 and result["intersection_lines"] == 1
    ms = pymeshlab.MeshSet()
    ms.load_new_mesh(str(out))
    assert ms.current_mesh().face_number() == result["faces"]
    records = lines.read_text().split("\n")
    assert sum(r.startswith("l ") for r in records) == result["intersection_edges"]


def test_cli_union_remesh_writes_the_regrid_that_stayed(tmp_path):
    # The regrid's layer is no longer the last one made (a second regrid from the exact union
    # may be made and one of them deleted): the CLI writes the one the pipeline kept. The case:
    # fuzz_union.py --models seed 10, whose exact union regrids better (15.89 degrees at 1%; 20.88
    # before stop 49, when line points within an input edge were spaced evenly: of the two lines
    # that close in on a corner at 20.88 degrees there, one has sizes growing from 0.007 to the
    # target along it, and its points near the corner moved by part of a segment against the
    # other line's, so the faces between them pair the points otherwise; 18.48 since stop 50,
    # when line points began to take small steps around their place, docs/remesh.md step 6).
    import json
    import subprocess
    import sys
    out, lines = tmp_path / "r.ply", tmp_path / "l.obj"
    bodies = _models_case_layers(10)
    parts = []
    for k in range(bodies.mesh_number()):
        bodies.set_current_mesh(k)
        parts.append(tmp_path / f"b{k}.ply")
        bodies.save_current_mesh(str(parts[-1]), binary=True)
    proc = subprocess.run([sys.executable, "-m", "meshregrid", "union", *map(str, parts), str(out), "--lines",
                           str(lines), "--remesh"], capture_output=True, text=True, check=True)
    result = json.loads(proc.stdout)
    assert result["remesh"]["from_exact_union"] and result["remesh"]["min_angle"] >= 18.0
    ms = pymeshlab.MeshSet()
    ms.load_new_mesh(str(out))
    assert ms.current_mesh().face_number() == result["remesh"]["faces"]
    # (PLY stores floats)
    assert angles(ms.current_mesh()).min() == pytest.approx(result["remesh"]["min_angle"], abs=1e-3)
    records = lines.read_text().split("\n")
    assert sum(r.startswith("l ") for r in records) == result["intersection_edges"]


def test_cli_union_components_of_one_file(tmp_path):
    import json
    import subprocess
    import sys
    out = tmp_path / "rabbit.ply"
    src = shared_mesh("multicomponent/rabbit.obj")
    proc = subprocess.run([sys.executable, "-m", "meshregrid", "union", str(src), str(out), "--components"],
                          capture_output=True, text=True, check=True)
    assert json.loads(proc.stdout)["bodies"] == 9


def benchmark_cluster_parts(n, subdiv):
    """bench_union.py's cluster: n icospheres of radius 0.5 at seed-1 random centres in a cube of
    side 0.9 n^(1/3), as (vertices, faces) per sphere."""
    ms = pymeshlab.MeshSet()
    ms.create_sphere(radius=0.5, subdiv=subdiv)
    v, f = ms.current_mesh().vertex_matrix(), ms.current_mesh().face_matrix()
    return [(v + c, f) for c in np.random.default_rng(1).random((n, 3)) * n ** (1 / 3) * 0.9]


def benchmark_cluster(n, subdiv):
    """The cluster as one layer of components; returns it and manifold3d's union volume."""
    parts = benchmark_cluster_parts(n, subdiv)
    ms = pymeshlab.MeshSet()
    ms.add_mesh(pymeshlab.Mesh(np.concatenate([v for v, _ in parts]),
                               np.concatenate([f + i * len(parts[0][0]) for i, (_, f) in enumerate(parts)])))
    return ms, reference([pymeshlab.Mesh(v, f) for v, f in parts])


def test_sliver_step_on_a_ten_sphere_cluster_leaves_no_face_under_5_degrees():
    # Icospheres (smallest angle 54 deg); the raw cut has about 400 faces under 5 deg.
    # Measured after the default sliver step: smallest angle 10.0 deg, volume 4e-15.
    ms, ref = benchmark_cluster(10, subdiv=3)
    r = unite(ms, bodies=COMPONENTS)
    assert r["bodies"] == 10
    assert angles(ms.mesh(1)).min() >= 5.0
    assert check_union(ms, 1) == pytest.approx(ref, rel=IMPROVED_VOLUME_RTOL)


def test_bug_radial_order_at_an_edge_of_1e_16_between_nearly_coincident_poles():
    # Found by fuzzing: C's top pole (0.6, 0.8, 0.5) and D's left pole (1.1 - 0.5, ...)
    # differ by one ulp, so the cut has an edge of length ~1e-16; the radial order of the
    # faces around it was taken from doubles and picked wrongly oriented faces (58
    # orientation conflicts, duplicated faces). The order is now decided exactly.
    ms = pymeshlab.MeshSet()
    for off in ((0.6, 0.8, 0.0), (1.1, 0.8, 0.5)):
        ms.create_sphere(radius=0.5, subdiv=2)
        ms.compute_matrix_from_translation(axisx=off[0], axisy=off[1], axisz=off[2])
    ref = reference([ms.mesh(0), ms.mesh(1)])
    r = unite(ms, bodies=LAYERS, sliver_angle=0)
    assert r["orientation_conflicts"] == 0
    assert check_union(ms, 2) == pytest.approx(ref, rel=EXACT_VOLUME_RTOL)


def test_bug_sphere_touching_a_cube_face_with_its_pole_was_removed():
    # Found by fuzzing: the sphere's extreme vertex (its +x pole) lies on the cube's face,
    # so the winding-number test at that vertex said "inside" and the sphere vanished.
    # Pieces are now tested at points that decide clearly (face centroids first).
    ms = pymeshlab.MeshSet()
    ms.create_sphere(radius=0.5, subdiv=2)
    ms.compute_matrix_from_translation(axisx=0, axisy=0.75, axisz=0.75)
    sphere_volume = ms.get_geometric_measures()["mesh_volume"]
    ms.create_cube(size=1)
    ms.compute_matrix_from_translation(axisx=1, axisy=0.5, axisz=0.5)
    r = unite(ms, bodies=LAYERS, sliver_angle=0)
    assert r["intersecting_pairs"] == 1  # they touch at one point
    assert check_union(ms, 2) == pytest.approx(sphere_volume + 1.0, rel=1e-12)
    assert ms.get_topological_measures()["connected_components_number"] == 2


def test_bug_identical_copy_inside_a_cluster_emptied_the_union():
    # Found by fuzzing: body 4 is an exact copy of body 2, so all its faces are dropped as
    # duplicates; the one piece of the arrangement was then tested against body 4 as if it
    # did not meet it, found "inside", and the result was empty. Bodies connected through
    # intersections are no longer used for that test.
    ms0 = pymeshlab.MeshSet()
    ms0.create_sphere(radius=0.5, subdiv=2)
    v, f = ms0.current_mesh().vertex_matrix(), ms0.current_mesh().face_matrix()
    spheres = [((0.5, 1, 0.5), 0.5), ((0.5, 1, 1), 1.5), ((0.5, 0, 0.5), 1.0), ((0, 1, 0.5), 1.0),
               ((0.5, 0, 0.5), 1.0), ((1, 0, 0), 1.0), ((0, 0.5, 0.5), 1.5)]
    ms = pymeshlab.MeshSet()
    for centre, radius in spheres:
        ms.add_mesh(pymeshlab.Mesh(v * radius * 2 + np.array(centre), f))
    ref = reference([ms.mesh(i) for i in range(len(spheres))])
    unite(ms, bodies=LAYERS, sliver_angle=0)
    assert check_union(ms, len(spheres)) == pytest.approx(ref, rel=EXACT_VOLUME_RTOL)


def _scaled_spheres(spheres):
    ms0 = pymeshlab.MeshSet()
    ms0.create_sphere(radius=0.5, subdiv=2)
    v, f = ms0.current_mesh().vertex_matrix(), ms0.current_mesh().face_matrix()
    ms = pymeshlab.MeshSet()
    for centre, radius in spheres:
        ms.add_mesh(pymeshlab.Mesh(v * radius * 2 + np.array(centre), f))
    return ms


def test_bug_sphere_inside_another_touching_it_was_kept():
    # Found by fuzzing (seed 324): a small sphere inside a big one, touching it, was
    # skipped by the inside test and kept (volume 3% too large).
    spheres = [((0, 0, 0.5), 1.5), ((0.5, 0.5, 0), 0.5), ((0.5, 0.5, 1), 0.5), ((0, 0, 1), 1.5)]
    ms = _scaled_spheres(spheres)
    ref = reference([ms.mesh(i) for i in range(len(spheres))])
    unite(ms, bodies=LAYERS, sliver_angle=0)
    assert check_union(ms, len(spheres)) == pytest.approx(ref, rel=EXACT_VOLUME_RTOL)


def test_bug_start_face_chosen_from_rounded_normals_at_a_shared_pole():
    # Found by fuzzing (seeds 654, 874, 934, 189): a sphere scaled by 1/2 about a pole of
    # another lies inside it, with faces around the shared pole tilted against the big
    # sphere's by ~1e-16. The fill's start face at the extreme vertex (that pole) was picked
    # from double-precision normals and could be the inner sphere's face; the fill then ran
    # on the wrong side (orientation conflicts). The choice is now exact.
    spheres = [((0, 1, 1), 0.5), ((1, 0.5, 0.5), 0.5), ((0.5, 0.5, 0.5), 1.0)]
    ms = _scaled_spheres(spheres)
    ref = reference([ms.mesh(i) for i in range(3)])
    r = unite(ms, bodies=LAYERS, sliver_angle=0)
    assert r["orientation_conflicts"] == 0
    topo = ms.get_topological_measures()
    assert topo["boundary_edges"] == 0 and topo["is_mesh_two_manifold"]
    assert ms.get_geometric_measures()["mesh_volume"] == pytest.approx(ref, rel=EXACT_VOLUME_RTOL)
    # Known limit: the exact result has faces 1e-16 apart here; rounded to doubles, 3-4 faces
    # cross (docs/union.md, "Limits"). The sliver step, whose moves are checked exactly,
    # is not asked to repair that.
    assert self_intersecting_faces(ms.current_mesh()) <= 8  # (MeshLab's flags vary by run)


def _noisy_blob():
    """tests/data/noisy_blob.obj read exactly (repr doubles), without an importer between."""
    path = pathlib.Path(__file__).resolve().parents[1] / "data" / "noisy_blob.obj"
    rows = [line.split() for line in path.read_text().splitlines()]
    v = np.array([[float(x) for x in r[1:]] for r in rows if r and r[0] == "v"])
    f = np.array([[int(x) - 1 for x in r[1:]] for r in rows if r and r[0] == "f"], dtype=np.int32)
    return v, f


def test_bug_vertex_removal_kept_a_line_edge_that_already_existed():
    # Found by fuzzing non-convex bodies (fuzz_union.py --nonconvex, seed 698): a noisy
    # blob and its copy shifted by (1/8, 0, 1/4). The sliver step removed a vertex on an
    # intersection line; the line's new edge between its two neighbours was kept without
    # the test that it is not an edge already, and got four faces (non-manifold output).
    v, f = _noisy_blob()
    ms = pymeshlab.MeshSet()
    ms.add_mesh(pymeshlab.Mesh(v, f))
    ms.add_mesh(pymeshlab.Mesh(v + np.array([0.125, 0.0, 0.25]), f))
    ref = reference([ms.mesh(0), ms.mesh(1)])
    unite(ms, bodies=LAYERS)
    assert check_union(ms, 2) == pytest.approx(ref, rel=IMPROVED_VOLUME_RTOL)


@pytest.mark.parametrize("sliver_angle,rtol", [(0.0, EXACT_VOLUME_RTOL), (10.0, IMPROVED_VOLUME_RTOL)])
@pytest.mark.parametrize("small_first", [False, True])
def test_bug_start_face_on_the_outer_edge_where_a_sphere_scaled_about_its_pole_touches(small_first, sliver_angle, rtol):
    # Found by fuzzing (12 of seeds 0-39999, e.g. 26974): the small sphere is the big one
    # scaled by 1/2 about its +x pole. The fill started on the face at the extreme vertex
    # whose normal leaned most towards +x: a small-sphere face tilted by 1e-16, inside the big
    # sphere. The union failed ("could not be told apart ... 8 ambiguous edges"). The start
    # face now lies on the outer edge at that vertex.
    spheres = [((0.5, 1, 0.5), 1.0), ((1, 1, 0.5), 0.5)]
    ms = _scaled_spheres(spheres[::-1] if small_first else spheres)
    big = ms.mesh(1 if small_first else 0)
    big_volume = pymeshlab.MeshSet()
    big_volume.add_mesh(big)
    ref = big_volume.get_geometric_measures()["mesh_volume"]
    r = unite(ms, bodies=LAYERS, sliver_angle=sliver_angle)
    assert r["orientation_conflicts"] == 0
    assert check_union(ms, 2) == pytest.approx(ref, rel=rtol)


@pytest.mark.parametrize("sliver_angle,rtol", [(0.0, EXACT_VOLUME_RTOL), (10.0, IMPROVED_VOLUME_RTOL)])
def test_bug_cubes_touching_along_an_edge_that_a_third_body_closes_at_both_ends(sliver_angle, rtol):
    # Found by fuzzing (seeds 1743, 2598, 4898 of fuzz_union.py): cubes B and C touch along
    # an edge; cube A's top face holds one end of the touching segment, a sphere crosses
    # the edge at the other. Around each end the surface is one fan, so both sheets' edges
    # joined the same two vertices: four faces on one edge. Each sheet now has its own.
    ms = pymeshlab.MeshSet()
    for offset in [(0.5, 0.25, 0.5), (1.0, 0.5, 0.25), (0.0, 1.25, 1.25)]:
        ms.create_cube(size=1)
        ms.meshing_surface_subdivision_midpoint(iterations=1)
        ms.compute_matrix_from_translation(axisx=offset[0], axisy=offset[1], axisz=offset[2])
    ms.create_sphere(radius=0.5, subdiv=2)
    ms.compute_matrix_from_translation(axisx=0.75, axisy=1.25, axisz=0.75)
    ref = reference([ms.mesh(i) for i in range(4)])
    r = unite(ms, bodies=LAYERS, sliver_angle=sliver_angle)
    assert r["doubled_edges_split"] >= 1
    assert check_union(ms, ms.mesh_number() - 1) == pytest.approx(ref, rel=rtol)


def test_sliver_step_on_a_coarse_fifty_sphere_cluster_keeps_the_volume():
    # 50 icospheres of 320 triangles (smallest angle 54 deg), the benchmark's seed. The raw
    # cut has about 1400 faces under 5 deg. Measured after the default sliver step: none
    # under 5 deg (smallest 6.26 deg), volume -1.6e-7. Before line vertices could slide part
    # of the way along their lines, 2 faces at 4.92 deg were left (two lines passing closer
    # than a sliver allows); before triple points could slide, 4 down to 1.9 deg.
    ms, ref = benchmark_cluster(50, subdiv=2)
    unite(ms, bodies=COMPONENTS)
    assert check_union(ms, 1) == pytest.approx(ref, rel=IMPROVED_VOLUME_RTOL)
    assert angles(ms.mesh(1)).min() >= 5.0


def test_sliver_step_checks_each_move_so_no_region_is_left_frozen():
    # 100 icospheres of 320 triangles, the benchmark's seed: spheres nearly touching, where a
    # sliver move can push a face through another sheet. Each move is checked exactly before
    # it is applied. Measured: no face under 5 deg (smallest 8.96 deg), volume -9.2e-7; 6 faces
    # down to 1.65 deg before vertex removal and slides along lines; with the former check
    # after the whole step (and a redo with the offending region frozen, its slivers
    # untreated) 19 faces down to 0.28 deg were left.
    ms, ref = benchmark_cluster(100, subdiv=2)
    unite(ms, bodies=COMPONENTS)
    assert check_union(ms, 1) == pytest.approx(ref, rel=IMPROVED_VOLUME_RTOL)
    assert angles(ms.mesh(1)).min() >= 5.0


@pytest.mark.parametrize("n,subdiv", [(200, 3), (800, 3), (2000, 2)])
def test_sliver_step_on_the_benchmark_clusters_leaves_no_face_under_5_degrees(n, subdiv):
    # bench_union.py's 200-sphere (256k triangles), 800-sphere (1.02M, the sweep's "about 1M")
    # and 2000-sphere (640k) clusters. Measured: smallest angle 7.85, 6.77 and 6.16 deg (8.91
    # for 200 before flips were planned first, 7.37 for 2000 before slides had to gain 10%), volume -4e-8, -1e-7 and -3e-7; before vertex
    # removal and slides along the lines 2 faces (4.38 deg, 200) and 46 faces (1.16 deg, 2000)
    # were under 5 deg.
    ms, ref = benchmark_cluster(n, subdiv=subdiv)
    unite(ms, bodies=COMPONENTS)
    assert check_union(ms, 1) == pytest.approx(ref, rel=IMPROVED_VOLUME_RTOL)
    assert angles(ms.mesh(1)).min() >= 5.0


def test_sliver_step_leaves_no_face_under_5_degrees_on_rabbit_obj():
    # rabbit.obj's own smallest angle is 4.84 deg, on its flat polygons. Measured: the union's
    # smallest is 5.65 deg since the input's flat slivers are flipped (25 flips); before, it
    # was 4.84 deg (4 faces under 5 deg, the input's), and before slides along the lines one
    # face at 4.44 deg was left.
    ms, parts = multicomponent("rabbit.obj")
    assert angles(ms.mesh(0)).min() < 5.0
    ms.set_current_mesh(0)
    r = unite(ms, bodies=COMPONENTS)
    assert r["flat_flips"] > 0
    assert angles(ms.mesh(ms.mesh_number() - 1)).min() >= 5.0
    assert r["slivers_left"] == 0

def test_sliver_step_on_box_stl_bends_lines_onto_plate_edges():
    # box.STL's plates nearly line up: intersection lines run 0.002 beside rows of plate
    # corners, and the strips between them hold needles that no move inside the strip can
    # mend. A line vertex may bend onto a crease vertex within the deviation bound.
    # Measured: no face under the input's own 0.449 deg, the reading (12 before line
    # bends, 4 with a deviation bound of 1e-3 on each move, which moves one after another
    # exceeded: up to 5.9e-3 of the diagonal; 1 with 1.5e-3 on all moves together); 465
    # under 5 deg with the input's flat slivers flipped (802 before, 994 before line bends,
    # 889 with the bound per move; the input has 1261).
    ms, parts = multicomponent("box.STL")
    input_min = angles(ms.mesh(0)).min()
    ms.set_current_mesh(0)
    r = unite(ms, bodies=COMPONENTS)
    out = angles(ms.mesh(ms.mesh_number() - 1)).min(axis=1)
    assert r["min_angle"] == pytest.approx(out.min(), abs=1e-9)
    assert out.min() >= input_min - 1e-9
    assert (out < 5).sum() <= 480
    assert r["flat_flips"] > 1000
    # The per-face reading: faces under 5 deg that are worse than the input face they lie
    # in (a flat flip's faces lie across both old ones: the worse one). Measured: 36 (of
    # the 465; the raw cut leaves 1871; 87 when a flipped face was measured against its
    # slot's old face only).
    assert r["slivers_left"] <= 40


def test_slivers_left_counts_the_cuts_own_slivers_before_the_sliver_step():
    # box.STL without the sliver step. Measured: 1871 faces under 5 deg worse than the input
    # face they lie in, of 3017 under 5 deg (the rest are the input's needles, or cut from
    # them and no worse).
    ms, parts = multicomponent("box.STL")
    ms.set_current_mesh(0)
    r = unite(ms, bodies=COMPONENTS, sliver_angle=0)
    union = ms.mesh(ms.mesh_number() - 1)
    out = angles(union).min(axis=1)
    assert 1500 <= r["slivers_left"] < (out < 5).sum()
    # They come selected in the union layer, so they can be seen; the input stays unselected.
    selected = union.face_selection_array()
    assert selected.sum() == r["slivers_left"]
    assert (out[selected] < 5).all()
    assert ms.mesh(0).selected_face_number() == 0


@pytest.mark.parametrize("name,bound", [
    # Measured (fraction of the diagonal; from the union, then to it): the bound is 2e-3,
    # checked at samples of every face a move makes (corners, points at a quarter, half and
    # three quarters of each edge, centroid), so faces can leave it a little between them.
    # Before, the bound was 1e-3 on each move alone:
    # - rabbit.obj 1.96e-3, 1.68e-3: a collapse on a folded star (a thin fin) had moved the
    #   surface 7.9e-3.
    # - box.STL 2.58e-3, 2.32e-3: moves one after another had bevelled a plate's edge by
    #   5.9e-3 of the diagonal (half the plate's thickness).
    # - ballA + ballB 1.21e-3, 1.01e-3 (1.9e-3 before).
    ("rabbit.obj", 3e-3),
    ("box.STL", 3e-3),
    ("balls", 3e-3),
])
def test_sliver_step_keeps_the_surface_near_the_exact_union(name, bound):
    if name == "balls":
        ms = load("multicomponent/ballA.off")
        ms.load_new_mesh(str(shared_mesh("multicomponent/ballB.off")))
        bodies, source = LAYERS, None
    else:
        ms, _ = multicomponent(name)
        bodies, source = COMPONENTS, 0
    if source is not None:
        ms.set_current_mesh(source)
    unite(ms, bodies=bodies, sliver_angle=0.0)
    exact = ms.current_mesh_id()
    if source is not None:
        ms.set_current_mesh(source)
    r = unite(ms, bodies=bodies)
    improved = ms.current_mesh_id()
    assert r["slivers_collapsed"] > 0
    diag = ms.mesh(exact).bounding_box().diagonal()
    assert one_way_hausdorff(ms, improved, exact, 200000) <= bound * diag
    assert one_way_hausdorff(ms, exact, improved, 200000) <= bound * diag


def _turned_half_a_turn(ms):
    """A copy of the current mesh turned by a floating-point half turn about the x axis
    through its centroid: a symmetric part then nearly coincides with its copy."""
    v, f = ms.current_mesh().vertex_matrix(), ms.current_mesh().face_matrix()
    c = v.mean(0)
    turn = np.array([[1, 0, 0], [0, np.cos(np.pi), -np.sin(np.pi)], [0, np.sin(np.pi), np.cos(np.pi)]])
    ms.add_mesh(pymeshlab.Mesh((v - c) @ turn.T + c, f))


@pytest.mark.parametrize("sliver_angle", [0.0, 10.0])
def test_bug_crossings_rounded_to_one_place_left_faces_with_coincident_corners(sliver_angle):
    # cad/part.off is symmetric about that axis: the copy lies within units in the last
    # place of the original, and crossings of the two sheets closer than that rounded to
    # one double. The edge between them had no length and its two faces no area (the
    # output's smallest angle was 0 and the exact check found them crossing their
    # neighbours); such edges are now merged (rounded_edges.h).
    ms = load("cad/part.off")
    _turned_half_a_turn(ms)
    ref = reference([ms.mesh(0), ms.mesh(1)])
    r = unite(ms, bodies=LAYERS, sliver_angle=sliver_angle)
    assert r["rounded_edges_merged"] > 0
    m = ms.current_mesh()
    v, f = m.vertex_matrix(), m.face_matrix()
    for z in range(3):
        assert not np.all(v[f[:, z]] == v[f[:, (z + 1) % 3]], axis=1).any()
    if sliver_angle > 0:
        assert check_union(ms, 2) == pytest.approx(ref, rel=IMPROVED_VOLUME_RTOL)
        assert angles(m).min() > 0.5
    else:
        topo = ms.get_topological_measures()
        assert topo["boundary_edges"] == 0 and topo["non_two_manifold_edges"] == 0
        assert ms.get_geometric_measures()["mesh_volume"] == pytest.approx(ref, rel=EXACT_VOLUME_RTOL)


def _fuzz_union():
    """scripts/fuzz_union.py, whose cases the regressions below replay."""
    import sys
    sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[2] / "scripts"))
    import fuzz_union
    return fuzz_union


def _shared_models():
    """fuzz_union.py's shared models (skips where they are missing: its loader would exit)."""
    fuzz_union = _fuzz_union()
    for name in fuzz_union.MODELS:
        shared_mesh(name)
    return fuzz_union.load_models()


def _models_case_layers(seed):
    """fuzz_union.py --models case `seed`, one layer per body (skips where the shared models
    are missing)."""
    fuzz_union = _fuzz_union()
    _, parts = fuzz_union.models_case(seed, _shared_models())
    ms = pymeshlab.MeshSet()
    for v, f in parts:
        ms.add_mesh(pymeshlab.Mesh(v, f))
    return ms


def _regrid_as_the_pipeline(ms, percent=1.0):
    """The current union regridded with the pipeline's remesh parameters (its lines kept)."""
    length = pymeshlab.PercentageValue(percent)
    return ms.meshing_advancing_front_remesh(target_length=length, min_line_length=length, improvement_iterations=5,
                                             use_selected_edges_as_ridges=True)


@pytest.mark.parametrize("seed", [0, 4])
def test_bug_regrid_of_a_union_whose_sliver_step_crumpled_a_flat_side_was_not_manifold(seed):
    # scripts/fuzz_union.py --models, seeds 0 and 4: cad/joint.off and two turned copies, one
    # shifted by whole sixteenths so that side faces coincide. The sliver step turns faces over
    # on a shared flat side (crumples: a face turned 165 degrees against all its neighbours);
    # the regrid meshed them as patches of their own on top of the side around them. Measured
    # at 1%, regridded from the stepped union: seed 4 had 15 points not manifold and faces
    # without area (13 from the pipeline), seed 0 none before crumples were dropped and 4 while
    # a crumple had to turn 120 degrees against every neighbour; now none.
    ms = _models_case_layers(seed)
    unite(ms, bodies=LAYERS)
    r = _regrid_as_the_pipeline(ms)
    assert r["unmeshed_sides"] == 0
    topo = ms.get_topological_measures()
    assert topo["boundary_edges"] == 0 and topo["is_mesh_two_manifold"]
    assert topo["non_two_manifold_vertices"] == 0
    assert angles(ms.current_mesh()).min() > 1.0


def test_regrid_slides_line_points_beside_the_wedges_of_a_joint_united_with_turned_copies():
    # scripts/fuzz_union.py --models, seed 8: cad/joint.off with turned copies, united and
    # regridded at 1% as the pipeline does. Its lines meet at 34 wedge tips (the narrowest 3.39
    # degrees, which no regrid keeping the lines can raise). Off the tips the smallest angle was
    # 4.54 degrees while a tip's fixed angle held the line points beside it; they slide now:
    # measured 13.93 (10.50 when this test came).
    ms = _models_case_layers(8)
    unite(ms, bodies=LAYERS)
    r = _regrid_as_the_pipeline(ms)
    assert r["unmeshed_sides"] == 0 and r["wedge_tips"] > 0
    assert r["min_angle"] == pytest.approx(min(r["min_wedge_angle"], r["min_angle_off_wedges"]), abs=1e-9)
    assert r["min_angle_off_wedges"] >= 9.0
    topo = ms.get_topological_measures()
    assert topo["boundary_edges"] == 0 and topo["is_mesh_two_manifold"]


def test_pipeline_regrid_of_joint_with_turned_copies_meshes_its_necks():
    # scripts/fuzz_union.py --models, seed 10 (cad/joint.off with turned copies) at 1%: before
    # the neck caps the pipeline kept the stepped union's regrid at 9.34 degrees; with them the
    # exact union's regrid, whose lines pass closer than 0.15 x target for stretches, reaches 20.88
    # (15.89 since stop 49's line spacing, 18.48 since stop 50's small steps of line points).
    from meshregrid import pipeline_union
    ms = _models_case_layers(10)
    r = pipeline_union.union(ms, remesh=True, target_percent=1.0)["remesh"]
    assert r["neck_points"] > 0 and r["unmeshed_sides"] == 0
    assert angles(ms.current_mesh()).min() >= 18.0
    topo = ms.get_topological_measures()
    assert topo["boundary_edges"] == 0 and topo["is_mesh_two_manifold"]



def test_pipeline_regrid_merges_corners_joined_by_a_tiny_line():
    # scripts/fuzz_union.py --models, seed 28 at 1%: two corners 0.0012 apart (0.05 x target) on
    # the exact union's lines made a face of 5.33 degrees; sharing one point (stop 51, docs/remesh.md
    # step 3, tiny lines) the worst is its 12.44-degree wedge and 15.11 off the wedges.
    from meshregrid import pipeline_union
    ms = _models_case_layers(28)
    r = pipeline_union.union(ms, remesh=True, target_percent=1.0)["remesh"]
    assert r["merged_corners"] >= 1 and r["unmeshed_sides"] == 0
    assert angles(ms.current_mesh()).min() >= 12.0
    assert r["min_angle_off_wedges"] >= 14.5
    topo = ms.get_topological_measures()
    assert topo["boundary_edges"] == 0 and topo["is_mesh_two_manifold"]

def _near_reference(far_parts, transform):
    """manifold3d's union volume of far_parts moved back near the origin (exact there, as in the fuzzer)."""
    fuzz_union = _fuzz_union()
    near = pymeshlab.MeshSet()
    for v, f in far_parts:
        near.add_mesh(pymeshlab.Mesh(fuzz_union.moved_back(v, transform), f))
    return reference([near.mesh(i) for i in range(near.mesh_number())])


def _nearly_coincident_blobs(seed):
    """fuzz_union.py --nonconvex's case for `seed` (kind 2 for these seeds: a noisy blob and
    copies of it scaled about one of its vertices or shifted on a grid)."""
    fuzz_union = _fuzz_union()
    _, sphere, _ = fuzz_union.shapes()
    kind, parts = fuzz_union.nonconvex_case(seed, sphere, None)
    assert kind == 2
    return parts


def _unite_nearly_coincident_blobs(seed, sliver_angle):
    """The union of seed's blobs, one layer each: the MeshSet, manifold3d's volume, the dictionary."""
    parts = _nearly_coincident_blobs(seed)
    ms = pymeshlab.MeshSet()
    for v, f in parts:
        ms.add_mesh(pymeshlab.Mesh(v, f))
    ref = reference([ms.mesh(i) for i in range(len(parts))])
    r = unite(ms, bodies=LAYERS, sliver_angle=sliver_angle)
    return ms, ref, r


def _assert_rounding_left_no_fault(ms, ref, sliver_angle):
    """The union layer has no face without area or with two corners at one place, no face
    that MeshLab flags and exact rationals confirm, is closed and manifold, and has the
    reference volume."""
    m = ms.current_mesh()
    v, f = m.vertex_matrix(), m.face_matrix()
    area = np.linalg.norm(np.cross(v[f[:, 1]] - v[f[:, 0]], v[f[:, 2]] - v[f[:, 0]]), axis=1)
    assert (area == 0).sum() == 0
    fresh = pymeshlab.MeshSet()
    fresh.add_mesh(pymeshlab.Mesh(v, f))
    fresh.compute_selection_by_self_intersections_per_face()
    flagged = np.nonzero(fresh.current_mesh().face_selection_array())[0]
    assert len(exactly_intersecting_faces(v, f, flagged)) == 0
    topo = ms.get_topological_measures()
    assert topo["boundary_edges"] == 0 and topo["is_mesh_two_manifold"]
    rtol = IMPROVED_VOLUME_RTOL if sliver_angle > 0 else EXACT_VOLUME_RTOL
    assert ms.get_geometric_measures()["mesh_volume"] == pytest.approx(ref, rel=rtol)


@pytest.mark.parametrize("seed", [104897, 105128])
@pytest.mark.parametrize("sliver_angle", [0.0, 10.0])
def test_bug_caps_rounded_onto_their_side_crossed_their_neighbours(seed, sliver_angle):
    # Found by fuzzing (fuzz_union.py --nonconvex, 2 of seeds 104600-105199): rounding put the
    # third corners of two faces on both sides of one edge onto that edge's line (angles of
    # 1e-14, 1e-14 and 180 degrees), overlapping each other and crossing (MeshLab's selection
    # and the exact re-check agreed), with or without the sliver step. Such caps are now
    # removed: split into their neighbour, or the two chains along the edge zipped, or, with
    # the apexes at one place, merged (rounded_caps.h).
    ms, ref, r = _unite_nearly_coincident_blobs(seed, sliver_angle)
    assert r["rounded_caps_split"] > 0
    _assert_rounding_left_no_fault(ms, ref, sliver_angle)
    m = ms.current_mesh()
    assert angles(m).max() < 179.9  # (was 180 up to rounding: the caps)


@pytest.mark.parametrize("sliver_angle", [0.0, 10.0])
def test_bug_a_cluster_of_rounded_crossings_beside_a_face_without_area_is_merged(sliver_angle):
    # Found by fuzzing (fuzz_union.py --nonconvex, seed 112943 of 112100-113599): four
    # crossings within a few units, and beside them faces that rounding had left without area
    # (corners on one line). Every merge of the cluster or of one of its edges was refused
    # because such a face had no turn to keep, which left two faces with two corners at one
    # place (and a smallest angle of 0 after the sliver step). A face without area may now
    # come out either way; the fold and crossing tests still hold it.
    ms, ref, r = _unite_nearly_coincident_blobs(112943, sliver_angle)
    assert r["rounded_edges_merged"] > 0
    # (No face without area there: so none with two corners at one place.)
    _assert_rounding_left_no_fault(ms, ref, sliver_angle)
    m = ms.current_mesh()
    if sliver_angle > 0:
        assert angles(m).min() > 2.0  # (2.82 measured; 0 before)


@pytest.mark.parametrize("sliver_angle", [0.0, 10.0])
def test_bug_a_bubble_that_rounding_closed_between_nearly_coincident_blobs_goes(sliver_angle):
    # Found by fuzzing (fuzz_union.py --nonconvex --transform, seed 117185 of 116700-117999):
    # the blobs scaled by 2^-41 and moved 23,000 of their scales from the origin, where
    # rounding is coarser. Two crossings landed on one place, and the two faces between them
    # and a third vertex became one triangle turned both ways: a bubble without volume. The
    # merge of the two crossings was refused (its star would not be a manifold), which left
    # two faces with two corners at one place, also after the sliver step. The bubble's two
    # faces now go with the merge, where their corners keep closed stars.
    fuzz_union = _fuzz_union()
    seed = 117185
    transform = fuzz_union.far_transform(seed, True)
    far = fuzz_union.moved(_nearly_coincident_blobs(seed), transform)
    ms = pymeshlab.MeshSet()
    for v, f in far:
        ms.add_mesh(pymeshlab.Mesh(v, f))
    r = unite(ms, bodies=LAYERS, sliver_angle=sliver_angle)
    assert r["rounded_edges_merged"] > 0
    m = ms.current_mesh()
    v, f = m.vertex_matrix(), m.face_matrix()
    corners = v[f]
    assert not (np.all(corners[:, 0] == corners[:, 1], axis=1) | np.all(corners[:, 1] == corners[:, 2], axis=1)
                | np.all(corners[:, 2] == corners[:, 0], axis=1)).any()
    # Measured near the origin (moving back is exact there, as in the fuzzer), against the
    # blobs moved back the same way.
    near = pymeshlab.MeshSet()
    near.add_mesh(pymeshlab.Mesh(fuzz_union.moved_back(v, transform), f))
    _assert_rounding_left_no_fault(near, _near_reference(far, transform), sliver_angle)


def test_bug_a_compensating_move_sees_the_faces_a_flip_just_made():
    # Found by fuzzing (fuzz_union.py --models --transform --params, seed 4528 of 4300-4799): a
    # CAD model and a turned copy, scaled by 2^26 and 24,000 scales from the origin, with the
    # sliver step at 24.4 deg, deviation 0.0146 and budget 1.9e-7. The arrangement was clean,
    # the step left 3 faces crossing another: a flip gave its volume back by moving a ring
    # vertex, whose crossing check looked the flipped faces up in the grid at their old boxes
    # and missed one. The flipped faces are now filed before the compensating move.
    fuzz_union = _fuzz_union()
    seed = 4528
    _, parts = fuzz_union.models_case(seed, _shared_models())
    transform = fuzz_union.far_transform(seed, True)
    params, budget = fuzz_union.sliver_params(seed, True)
    far = fuzz_union.moved(parts, transform)
    ms = pymeshlab.MeshSet()
    for v, f in far:
        ms.add_mesh(pymeshlab.Mesh(v, f))
    r = unite(ms, bodies=LAYERS, **params)
    assert r["slivers_collapsed"] > 0 and r["rounded_edges_merged"] == 0
    m = ms.current_mesh()
    near = pymeshlab.MeshSet()  # measured near the origin, where moving back is exact
    near.add_mesh(pymeshlab.Mesh(fuzz_union.moved_back(m.vertex_matrix(), transform), m.face_matrix()))
    ref = _near_reference(far, transform)
    _assert_rounding_left_no_fault(near, ref, params["sliver_angle"])
    assert near.get_geometric_measures()["mesh_volume"] == pytest.approx(ref, rel=budget)


def test_bug_a_patch_meshed_first_took_an_edge_of_a_line_between_two_corners():
    # Found by fuzzing (fuzz_union_regrid.py, seed 281 of 265-312, at 1%): cad/part.off united
    # with its copies and regridded was not two-manifold, one edge with four faces. Two corners
    # 0.005 apart are joined by a one-segment intersection line; a patch meshed before the two
    # patches beside that line had both corners on its border and joined them by an edge of its
    # own, and the line's patches then put their faces on it too. Such a patch is now meshed
    # again with the line segments barred to it (remesh.cpp, `remeshed_off_lines`).
    from meshregrid import pipeline_union
    _, parts = _fuzz_union().models_case(281, _shared_models())
    for relax in (False, True):
        ms = pymeshlab.MeshSet()
        for v, f in parts:
            ms.add_mesh(pymeshlab.Mesh(v, f))
        regrid = pipeline_union.union(ms, remesh=True, target_percent=1.0, relax_wedges=relax)["remesh"]
        assert regrid["remeshed_off_lines"] > 0
        assert regrid["unmeshed_sides"] == 0 and regrid["non_manifold_points"] == 0
        topo = ms.get_topological_measures()
        assert topo["boundary_edges"] == 0 and topo["is_mesh_two_manifold"]
        assert topo["non_two_manifold_edges"] == 0 and topo["non_two_manifold_vertices"] == 0


def test_bug_a_thin_strip_whose_one_layer_did_not_close():
    # Found by fuzzing (fuzz_union_regrid.py, seed 492 of 446-500, at 1%): cad/joint.off united
    # with two copies; the regrid of the exact union left 77 sides open (and the stepped union's
    # regrid was not two-manifold, so the pipeline had no closed regrid to keep). A strip narrower
    # than a tenth of the size gets one layer of faces by ear clipping, and there an ear it
    # needed was refused. Such a strip is now meshed as any patch (remesh.cpp, mesh_patch).
    from meshregrid import pipeline_union
    _, parts = _fuzz_union().models_case(492, _shared_models())
    ms = pymeshlab.MeshSet()
    for v, f in parts:
        ms.add_mesh(pymeshlab.Mesh(v, f))
    regrid = pipeline_union.union(ms, remesh=True, target_percent=1.0, sliver_angle=0.0)["remesh"]
    assert regrid["thin_patches"] >= 1
    assert regrid["unmeshed_sides"] == 0 and regrid["unmeshed_patches"] == 0 and regrid["non_manifold_points"] == 0
    topo = ms.get_topological_measures()
    assert topo["boundary_edges"] == 0 and topo["is_mesh_two_manifold"]


def _quarter_turned(v, turns):
    """v turned about its centre by the given quarter turns about x, y, z (fuzz_union.py --models)."""
    a = np.array(turns) * np.pi / 2
    rx = np.array([[1, 0, 0], [0, np.cos(a[0]), -np.sin(a[0])], [0, np.sin(a[0]), np.cos(a[0])]])
    ry = np.array([[np.cos(a[1]), 0, np.sin(a[1])], [0, 1, 0], [-np.sin(a[1]), 0, np.cos(a[1])]])
    rz = np.array([[np.cos(a[2]), -np.sin(a[2]), 0], [np.sin(a[2]), np.cos(a[2]), 0], [0, 0, 1]])
    centre = v.mean(0)
    return (v - centre) @ (rz @ ry @ rx).T + centre


@pytest.mark.parametrize("sliver_angle", [0.0, 10.0])
def test_bug_rounded_clusters_on_nearly_coincident_sheets_left_faces_without_area(sliver_angle):
    # Found by fuzzing (fuzz_union.py --models, seed 626): cad/fandisk.obj and two copies
    # turned by quarter turns (cosines of 6e-17: the sheets nearly coincide wherever the part
    # is symmetric). Rounding left 6,900 ends of edges within units in the last place; 660 of
    # the merges were refused because a face at the cluster lay folded on a coplanar
    # neighbour already, before the merge. 311 faces without area were left (209 after the
    # sliver step, 220 before the cap repair), and with the sliver step 5 faces crossed. A
    # fold the face had before no longer refuses a merge (rounded_edges.cpp): none is left.
    ms = load("cad/fandisk.obj")
    v, f = ms.current_mesh().vertex_matrix(), ms.current_mesh().face_matrix()
    for turns in ((0, 3, 2), (2, 3, 0)):
        ms.add_mesh(pymeshlab.Mesh(_quarter_turned(v, turns), f))
    ref = reference([ms.mesh(i) for i in range(3)])
    r = unite(ms, bodies=LAYERS, sliver_angle=sliver_angle)
    assert r["rounded_edges_merged"] > 6000
    _assert_rounding_left_no_fault(ms, ref, sliver_angle)
    m = ms.current_mesh()
    if sliver_angle > 0:
        assert angles(m).min() > 0.5  # 0.84 measured (0 before)


def test_pipeline_regrid_suppresses_the_inputs_short_creases_like_the_remesh_filter():
    # rocker-arm.obj as its own union, regridded at 1%: with min_line_length at once the target
    # (the pipeline's before stop 49) its short creases stayed as lines and the regrid kept an
    # input face of 6.28 degrees between three of its corners; at twice the target (the remesh
    # filter's own ratio, now the pipeline's) 16.52.
    from meshregrid import pipeline_union
    worst = {}
    for factor in (1.0, 2.0):
        ms = load("organic/rocker-arm.obj")
        r = pipeline_union.union(ms, bodies="layers", remesh=True, target_percent=1.0,
                                 regrid_exact_union_too=False, min_line_length_factor=factor)
        topo = ms.get_topological_measures()
        assert r["remesh"]["unmeshed_sides"] == 0 and topo["boundary_edges"] == 0 and topo["is_mesh_two_manifold"]
        worst[factor] = angles(ms.current_mesh()).min()
    assert worst[1.0] < 7.0 and worst[2.0] >= 16.0


@pytest.mark.parametrize("factor", [-1.0, float("nan"), float("inf")])
def test_pipeline_refuses_a_bad_min_line_length_factor_before_uniting(factor):
    from meshregrid import pipeline_union
    ms = pymeshlab.MeshSet()
    ms.create_sphere(subdiv=2)
    before = snapshot(ms.current_mesh())
    with pytest.raises(ValueError, match="min_line_length_factor"):
        pipeline_union.union(ms, bodies="components", remesh=True, min_line_length_factor=factor)
    assert ms.mesh_number() == 1
    assert_unchanged(before, ms.current_mesh())
