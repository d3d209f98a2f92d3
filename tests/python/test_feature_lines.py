"""Regression tests of compute_feature_lines_and_patches through PyMeshLab."""
import math

import numpy as np
import pymeshlab
import pytest

from conftest import assert_unchanged, load, raises_on, snapshot


def features(ms, **kw):
    return ms.compute_feature_lines_and_patches(**kw)


def test_cube_and_subdivided_cube():
    ms = pymeshlab.MeshSet()
    ms.create_cube()
    r = features(ms)
    assert (r["ridge_edges"], r["corners"], r["lines"], r["patches"]) == (12, 8, 12, 6)
    ms.meshing_surface_subdivision_midpoint(iterations=3)
    r = features(ms)
    assert (r["corners"], r["lines"], r["patches"]) == (8, 12, 6)
    assert r["ridge_edges"] == 12 * 8


def test_cylinder_has_two_closed_lines_and_three_patches():
    ms = pymeshlab.MeshSet()
    ms.create_cone(r0=1, r1=1, h=2, subdiv=48)
    r = features(ms)
    assert (r["patches"], r["lines"], r["corners"]) == (3, 2, 0)


def test_sphere_is_one_patch_without_lines():
    ms = pymeshlab.MeshSet()
    ms.create_sphere(subdiv=3)
    r = features(ms)
    assert (r["patches"], r["lines"], r["ridge_edges"]) == (1, 0, 0)


def test_outputs_patch_ids_colours_corners_and_lines_layer():
    ms = pymeshlab.MeshSet()
    ms.create_cube()
    ms.meshing_surface_subdivision_midpoint(iterations=2)
    r = features(ms, create_lines_layer=True)
    m = ms.mesh(0)
    ids = m.face_custom_scalar_attribute_array("patch_id")
    assert sorted(set(ids.astype(int))) == list(range(6))
    assert np.all(np.bincount(ids.astype(int)) == m.face_number() // 6)
    assert m.selected_vertex_number() == 8
    colours = m.face_color_matrix()
    assert len({tuple(np.round(c, 4)) for c in colours}) == 6
    assert ms.mesh_number() == 2
    lines = ms.mesh(1)
    assert lines.edge_number() == r["ridge_edges"]
    assert lines.face_number() == 0


def edge_set_from_selection(ms, mesh_id):
    """The face-edge selection of a mesh as a set of coordinate pairs (via MeshLab's own polyline filter)."""
    ms.set_current_mesh(mesh_id)
    ms.generate_polyline_from_selected_edges()
    poly = ms.current_mesh()
    v = poly.vertex_matrix()
    edges = poly.edge_matrix()
    key = lambda p: tuple(np.round(p, 9))
    result = {tuple(sorted((key(v[a]), key(v[b])))) for a, b in edges}
    ms.delete_current_mesh()
    ms.set_current_mesh(mesh_id)
    return result


@pytest.mark.parametrize("name", ["cad/fandisk.obj", "cad/joint.off", "cad/part.off"])
def test_ridges_equal_meshlab_crease_selection(name):
    angle = 30.0
    ms = load(name)
    ms.compute_selection_crease_per_edge(angledegneg=-angle, angledegpos=angle)
    theirs = edge_set_from_selection(ms, 0)
    r = features(ms, ridge_angle=angle)
    ours = edge_set_from_selection(ms, 0)
    assert r["boundary_edges"] == 0 and r["non_manifold_edges"] == 0  # closed models
    assert len(theirs) > 0
    assert ours == theirs
    assert r["ridge_edges"] == len(ours)


@pytest.mark.parametrize("name", ["cad/fandisk.obj", "cad/joint.off", "cad/part.off"])
def test_patch_count_stable_under_rigid_rotation(name):
    ms = load(name)
    before = features(ms)
    ms.compute_matrix_from_rotation(rotaxis="custom axis", angle=37.0, customaxis=[0.3, -0.5, 0.8])
    ms.compute_matrix_from_translation(axisx=3.0, axisy=-1.0, axisz=2.0)
    after = features(ms)
    assert after["patches"] == before["patches"]
    assert after["lines"] == before["lines"]
    assert after["corners"] == before["corners"]


def test_min_patch_faces_merges_small_patches_on_a_scan():
    ms = load("organic/stanford-bunny.obj")
    plain = features(ms, ridge_angle=20)
    merged = features(ms, ridge_angle=20, min_patch_faces=50)
    assert plain["patches"] > merged["patches"] >= 1
    ids = ms.current_mesh().face_custom_scalar_attribute_array("patch_id").astype(int)
    counts = np.bincount(ids)
    assert len(counts) == merged["patches"]
    # a patch smaller than 50 survives only if it had no neighbour (a separate component)
    assert (counts < 50).sum() <= plain["boundary_edges"]


def lines_layer_edges(name, **kw):
    """Feature filter on a fresh copy of a shared mesh: its dictionary and the lines layer's
    segments as sorted coordinate pairs."""
    ms = load(name)
    r = features(ms, create_lines_layer=True, color_patches=False, **kw)
    m = ms.mesh(1)  # the lines layer is the second mesh of the fresh MeshSet
    v, e = m.vertex_matrix(), m.edge_matrix()
    return r, {tuple(sorted((tuple(v[a]), tuple(v[b])))) for a, b in e}


def test_min_line_length_drops_short_dangling_creases_of_a_scan_and_keeps_the_boundary():
    """At 30 degrees the bunny scan has about a thousand corners, most on creases shorter than 1%
    of the diagonal; min_line_length = 1% drops those with an open end (and short loops): fewer
    ridges, corners and lines, only ridges the strict mode has, and every boundary edge stays."""
    name = "organic/stanford-bunny.obj"
    length = 0.01 * load(name).current_mesh().bounding_box().diagonal()
    strict, strict_segments = lines_layer_edges(name, ridge_angle=30)
    zero, _ = lines_layer_edges(name, ridge_angle=30, min_line_length=pymeshlab.PureValue(0.0))
    assert zero == {**strict, "time_ms": zero["time_ms"]}
    assert strict["suppressed_lines"] == 0
    kept, kept_segments = lines_layer_edges(name, ridge_angle=30, min_line_length=pymeshlab.PureValue(length))
    assert kept["suppressed_lines"] > 100
    assert kept["ridge_edges"] + kept["suppressed_ridge_edges"] == strict["ridge_edges"]
    assert kept["corners"] < 0.7 * strict["corners"]
    assert kept_segments <= strict_segments
    assert kept["boundary_edges"] == strict["boundary_edges"] > 0
    assert kept["ridge_edges"] >= kept["boundary_edges"]


def test_deterministic():
    ms = load("cad/fandisk.obj")
    a = features(ms)
    ids_a = ms.current_mesh().face_custom_scalar_attribute_array("patch_id").copy()
    b = features(ms)
    ids_b = ms.current_mesh().face_custom_scalar_attribute_array("patch_id")
    a.pop("time_ms"), b.pop("time_ms")
    assert a == b
    np.testing.assert_array_equal(ids_a, ids_b)


# ---- bad input ------------------------------------------------------------

def test_empty_mesh_raises_and_is_unchanged():
    ms = pymeshlab.MeshSet()
    ms.create_cube()
    ms.set_selection_all()
    ms.meshing_remove_selected_vertices()
    assert ms.current_mesh().vertex_number() == 0
    with raises_on(ms, "empty"):
        features(ms)
    assert ms.current_mesh().vertex_number() == 0


def test_point_cloud_raises_and_is_unchanged():
    ms = pymeshlab.MeshSet()
    ms.add_mesh(pymeshlab.Mesh(vertex_matrix=np.random.default_rng(1).random((50, 3))))
    before = snapshot(ms.current_mesh())
    with raises_on(ms, "no faces"):
        features(ms)
    assert_unchanged(before, ms.current_mesh())


def test_nan_coordinates_raise_and_mesh_is_unchanged():
    ms = pymeshlab.MeshSet()
    ms.create_cube()
    v = ms.current_mesh().vertex_matrix().copy()
    f = ms.current_mesh().face_matrix()
    v[3, 1] = math.nan
    ms.add_mesh(pymeshlab.Mesh(vertex_matrix=v, face_matrix=f))
    before = snapshot(ms.current_mesh())
    with raises_on(ms, "NaN"):
        features(ms)
    after = snapshot(ms.current_mesh())
    np.testing.assert_array_equal(np.isnan(before[0]), np.isnan(after[0]))
    np.testing.assert_array_equal(before[1], after[1])
    assert not ms.current_mesh().has_face_color()  # nothing was written


@pytest.mark.parametrize("bad", [dict(ridge_angle=0.0), dict(ridge_angle=190.0), dict(corner_angle=-5.0),
                                 dict(min_patch_faces=-1), dict(min_line_length=pymeshlab.PureValue(-1.0))])
def test_bad_parameters_raise(bad):
    ms = pymeshlab.MeshSet()
    ms.create_cube()
    before = snapshot(ms.current_mesh())
    with raises_on(ms, "must"):
        features(ms, **bad)
    assert_unchanged(before, ms.current_mesh())


def test_non_manifold_vertices_and_open_borders_work():
    ms = load("healing/angle_block.STL")  # 33 non-manifold vertices, T-junction cracks
    r = features(ms)
    assert r["boundary_edges"] == ms.get_topological_measures()["boundary_edges"]
    assert r["ridge_edges"] >= r["boundary_edges"]
    assert r["patches"] >= 1


def test_non_manifold_edge_is_a_ridge():
    # three fins sharing one edge
    v = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, -1, 0.2], [0, 0, 1]], dtype=float)
    f = np.array([[0, 1, 2], [1, 0, 3], [0, 1, 4]])
    ms = pymeshlab.MeshSet()
    ms.add_mesh(pymeshlab.Mesh(vertex_matrix=v, face_matrix=f))
    r = features(ms)
    assert r["non_manifold_edges"] == 1
    assert r["patches"] == 3


def test_cli_features(tmp_path):
    from meshregrid.cli import main
    from conftest import shared_mesh
    out = tmp_path / "part.ply"
    lines = tmp_path / "lines.ply"
    assert main(["features", str(shared_mesh("cad/part.off")), str(out), "--lines", str(lines)]) == 0
    ms = pymeshlab.MeshSet()
    ms.load_new_mesh(str(out))
    assert ms.current_mesh().has_face_color()
    assert lines.stat().st_size > 0


def test_keep_folded_slivers_keeps_the_needles_of_a_cad_union():
    """box.STL united leaves needles 0.14 long at its plates' corners, folded more than 60 degrees
    against their neighbours. At min_line_length = 2% the suppression drops their borders (the
    remesher's front cannot cross those folds); keep_folded_slivers keeps them: no folded sliver
    dropped, and more ridges and patches."""
    ms = load("multicomponent/box.STL")
    ms.generate_surface_intersection_union(bodies=1)
    union = ms.current_mesh_id()
    length = pymeshlab.PercentageValue(2.0)
    plain = features(ms, use_selected_edges_as_ridges=True, min_line_length=length, color_patches=False)
    ms.set_current_mesh(union)
    kept = features(ms, use_selected_edges_as_ridges=True, min_line_length=length, color_patches=False,
                    keep_folded_slivers=True)
    assert plain["suppressed_folded_slivers"] > 0
    assert kept["suppressed_folded_slivers"] == 0
    assert kept["ridge_edges"] > plain["ridge_edges"]
    assert kept["patches"] > plain["patches"]
    assert kept["suppressed_lines"] < plain["suppressed_lines"]
