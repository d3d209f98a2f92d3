"""Regression tests of meshing_heal_patch_gaps through PyMeshLab: the shared
CAD patch sets, patch-gap cases generated from closed meshes, and bad input."""
import numpy as np
import pymeshlab
import pytest

from conftest import assert_unchanged, load, raises_on, snapshot
import patch_gap_cases as cases
from meshregrid.quality import one_way_hausdorff

Pct = pymeshlab.PercentageValue
Abs = pymeshlab.PureValue


def heal(ms, **kw):
    return ms.meshing_heal_patch_gaps(**kw)


def arrays(ms, mesh_id=None):
    m = ms.current_mesh() if mesh_id is None else ms.mesh(mesh_id)
    return m.vertex_matrix(), m.face_matrix()


def mesh_set(V, F, P=None):
    ms = pymeshlab.MeshSet()
    m = pymeshlab.Mesh(vertex_matrix=np.asarray(V, float), face_matrix=np.asarray(F, np.int32))
    if P is not None:
        m.add_face_custom_scalar_attribute(np.asarray(P, float), "patch_id")
    ms.add_mesh(m, "patches")
    return ms


def hausdorff_to(ms, sampled, target, diag):
    """Largest distance from points sampled on `sampled` (vertices, edges, faces) to `target`."""
    return one_way_hausdorff(ms, sampled, target, 20000, maxdist=diag)


def assert_sound(V, F):
    """Manifold and one orientation."""
    assert cases.non_manifold_edges(F) == 0
    assert cases.consistently_oriented(F)


# ---- the box of six independently triangulated faces (the brief's case) -------------

@pytest.mark.parametrize("apart", [0.0, 0.01])
def test_box_of_six_faces_closes_t_junctions_and_gaps(apart):
    # Faces 'apart' away from each other along every cube edge; T-junctions on all of them.
    V, F, P = cases.box_of_six_faces(offset=apart / np.sqrt(2))
    ms = mesh_set(V, F)
    tol = 0.02
    r = heal(ms, vertex_tolerance=Abs(tol))
    HV, HF = arrays(ms)
    assert r["patches"] == 6 and r["t_junctions_split"] > 0
    assert r["boundary_edges_before"] > 0
    assert r["boundary_edges_after"] == 0 == cases.boundary_edges(HF)
    assert_sound(HV, HF)
    assert cases.signed_volume(HV, HF) == pytest.approx(8.0, rel=0.03)  # outward, cube-sized
    assert r["largest_move"] <= tol
    assert r["groups"] == 6 and r["feature_edges"] > 0  # the cube's sides, bounded by its edges


# ---- the shared CAD patch sets ---------------------------------------------------------

# (file, tolerance in % of the bbox diagonal, expected to end watertight)
SHARED = [
    ("healing/boeing.off", 0.01, True),        # 122 patches, duplicated seams, mixed orientation
    ("healing/angle_block.STL", 0.01, True),   # T-junction cracks, non-manifold vertices
    ("healing/ALSTOM_TEST4.off", 0.1, False),  # 6 patches; some borders are more than 1% apart
]


@pytest.mark.parametrize("name,tol_pct,closes", SHARED)
def test_shared_patch_sets(name, tol_pct, closes):
    ms = load(name)
    before = snapshot(ms.current_mesh())
    diag = ms.current_mesh().bounding_box().diagonal()
    r = heal(ms, vertex_tolerance=Pct(tol_pct))
    open_faces = ms.current_mesh().selected_face_number()
    assert ms.mesh_number() == 2
    assert_unchanged(before, ms.mesh(0))  # the input layer is untouched
    HV, HF = arrays(ms)
    assert_sound(HV, HF)
    assert r["non_manifold_edges_after"] == 0
    assert r["largest_move"] <= tol_pct / 100 * diag
    assert ms.get_topological_measures()["connected_components_number"] == 1
    # Healing moves the surface by at most the tolerance.
    assert hausdorff_to(ms, 1, 0, diag) <= tol_pct / 100 * diag * 1.001
    if closes:
        assert r["boundary_edges_after"] == 0 == cases.boundary_edges(HF)
        assert r["open_loops"] == 0
    else:
        assert r["boundary_edges_after"] <= 0.5 * r["boundary_edges_before"]
        assert r["gaps_left"] > 0 and r["largest_gap"] > 0  # what stays open is reported
        assert open_faces > 0  # ... and selected


def test_boeing_groups_patches_into_regions_bounded_by_features():
    ms = load("healing/boeing.off")
    r = heal(ms, vertex_tolerance=Pct(0.01), feature_angle=30)
    groups = ms.current_mesh().face_custom_scalar_attribute_array("group_id")
    assert r["patches"] == 122
    assert 1 < r["groups"] < r["patches"]
    assert len(np.unique(groups)) == r["groups"]
    assert r["feature_edges"] > 0
    # A larger feature angle can only merge groups.
    ms.set_current_mesh(0)
    r2 = heal(ms, vertex_tolerance=Pct(0.01), feature_angle=60)
    assert r2["groups"] <= r["groups"]


# ---- generated cases from closed CAD meshes --------------------------------------------

def patched(name):
    """A closed shared mesh and its stage-1 patches."""
    ms = load(name)
    ms.compute_feature_lines_and_patches(ridge_angle=40)
    m = ms.current_mesh()
    P = m.face_custom_scalar_attribute_array("patch_id").astype(int)
    return m.vertex_matrix(), m.face_matrix(), P, m.bounding_box().diagonal()


@pytest.mark.parametrize("name", ["cad/part.off", "cad/joint.off"])
@pytest.mark.parametrize("kind", cases.KINDS)
def test_generated_damage_below_tolerance_heals_close_to_the_original(name, kind):
    V, F, P, diag = patched(name)
    width = 0.002 * diag
    DV, DF, DP = cases.make_case(V, F, P, kind, width)
    assert cases.boundary_edges(DF) > 0
    ms = mesh_set(DV, DF, DP)
    ms.add_mesh(pymeshlab.Mesh(V, F), "original")
    ms.set_current_mesh(0)
    r = heal(ms, vertex_tolerance=Abs(2 * width), patch_source=1)
    healed = ms.current_mesh_id()
    HV, HF = arrays(ms)
    assert r["patches"] == len(np.unique(P))
    assert r["boundary_edges_after"] == 0 == cases.boundary_edges(HF)
    assert_sound(HV, HF)
    assert cases.signed_volume(HV, HF) > 0
    if kind in ("duplicate", "tjunction"):
        assert r["largest_move"] <= 1e-12 * diag  # round-off of the split points only
    if kind == "duplicate":
        assert len(HV) == len(V)
    # The healed surface stays within the damage width of the original, both ways.
    assert hausdorff_to(ms, healed, 1, diag) < width
    assert hausdorff_to(ms, 1, healed, diag) < width


def test_generated_gaps_above_tolerance_stay_open_and_are_reported():
    V, F, P, diag = patched("cad/part.off")
    width = 0.006 * diag
    DV, DF, DP = cases.make_case(V, F, P, "gap", width)
    ms = mesh_set(DV, DF, DP)
    tol = width / 3
    r = heal(ms, vertex_tolerance=Abs(tol), patch_source=1)
    assert r["boundary_edges_after"] >= 0.9 * r["boundary_edges_before"]
    assert r["largest_move"] <= tol
    assert r["gaps_left"] > 0
    assert tol < r["largest_gap"] <= 2 * width


# ---- patch sources, outputs, determinism ---------------------------------------------

def test_visible_layers_are_patches():
    V, F, P = cases.box_of_six_faces(offset=0.003)
    ms = pymeshlab.MeshSet()
    for k in range(6):
        faces = F[P == k]
        used, local = np.unique(faces, return_inverse=True)
        ms.add_mesh(pymeshlab.Mesh(V[used], local.reshape(-1, 3).astype(np.int32)), f"side {k}")
    r = heal(ms, vertex_tolerance=Abs(0.02), patch_source=2)
    assert ms.mesh_number() == 7
    assert r["patches"] == 6 and r["boundary_edges_after"] == 0
    patch = ms.current_mesh().face_custom_scalar_attribute_array("patch_id")
    assert sorted(np.unique(patch)) == list(range(6))


def test_open_borders_selected_and_moves_in_vertex_quality():
    V, F, P, diag = patched("cad/part.off")
    DV, DF, DP = cases.make_case(V, F, P, "gap", 0.002 * diag)
    ms = mesh_set(DV, DF, DP)
    heal(ms, vertex_tolerance=Abs(0.004 * diag), patch_source=1)
    m = ms.current_mesh()
    assert m.selected_face_number() == 0  # nothing left open
    moves = m.vertex_scalar_array()
    assert moves.max() <= 0.004 * diag and moves.max() > 0


def test_same_input_gives_same_output():
    V, F, P = cases.box_of_six_faces(offset=0.004)
    out = []
    for _ in range(2):
        ms = mesh_set(V, F)
        heal(ms, vertex_tolerance=Abs(0.02))
        out.append(arrays(ms))
    np.testing.assert_array_equal(out[0][0], out[1][0])
    np.testing.assert_array_equal(out[0][1], out[1][1])


# ---- bad input -------------------------------------------------------------------------

def test_point_cloud_is_rejected():
    ms = pymeshlab.MeshSet()
    ms.add_mesh(pymeshlab.Mesh(vertex_matrix=np.random.default_rng(1).random((20, 3))))
    with raises_on(ms, "no faces"):
        heal(ms)


def test_nan_coordinates_are_rejected_and_input_untouched():
    V, F, P = cases.box_of_six_faces()
    V[3, 1] = np.nan
    ms = mesh_set(V, F)
    before = snapshot(ms.current_mesh())
    with raises_on(ms, "NaN"):
        heal(ms, vertex_tolerance=Abs(0.01))
    assert ms.mesh_number() == 1
    assert_unchanged(before, ms.current_mesh())


@pytest.mark.parametrize("kw,match", [
    (dict(vertex_tolerance=Abs(0)), "vertex_tolerance"),
    (dict(vertex_tolerance=Abs(-1)), "vertex_tolerance"),
    (dict(vertex_tolerance=Pct(50)), "quarter"),
    (dict(feature_angle=0), "feature_angle"),
    (dict(patch_source=1), "patch_id"),
])
def test_bad_parameters_are_rejected(kw, match):
    V, F, P = cases.box_of_six_faces()
    ms = mesh_set(V, F)
    with raises_on(ms, match):
        heal(ms, **kw)
    assert ms.mesh_number() == 1


# ---- robustness: every shared triangle mesh ------------------------------------------

ALL_SHARED = ["cad/blade.off", "cad/fandisk.obj", "cad/joint.off", "cad/part.off",
              "organic/rocker-arm.obj", "organic/stanford-bunny.obj", "multicomponent/ballA.off",
              "multicomponent/box.STL", "multicomponent/rabbit.obj", "quad/spot_control_mesh.obj",
              "quad/torus_quad.off"]


@pytest.mark.parametrize("name", ALL_SHARED)
def test_every_shared_mesh_heals_without_damage(name):
    ms = load(name)
    before = ms.get_topological_measures()
    diag = ms.current_mesh().bounding_box().diagonal()
    r = heal(ms, vertex_tolerance=Pct(0.01))
    assert r["largest_move"] <= 1e-4 * diag
    assert r["boundary_edges_after"] <= r["boundary_edges_before"]
    # Healing never adds non-manifold edges.
    assert r["non_manifold_edges_after"] <= before["non_two_manifold_edges"]


@pytest.mark.parametrize("values,match", [
    (lambda n: np.zeros((n, 3)), "not a scalar attribute"),  # a point attribute of that name
    (lambda n: np.full(n, 1e30), "huge value"),
])
def test_unusable_patch_id_attribute_is_rejected(values, match):
    V, F, P = cases.box_of_six_faces()
    ms = mesh_set(V, F)
    m = ms.current_mesh()
    if values(1).ndim == 2:
        m.add_face_custom_point_attribute(values(m.face_number()), "patch_id")
    else:
        m.add_face_custom_scalar_attribute(values(m.face_number()), "patch_id")
    before = snapshot(m)
    with raises_on(ms, match):
        heal(ms, vertex_tolerance=Abs(0.01), patch_source=1)
    assert ms.mesh_number() == 1
    assert_unchanged(before, ms.current_mesh())
