"""meshing_advancing_front_remesh through PyMeshLab: topology, features, and quality
against MeshLab's isotropic remesher run in the same test at the same target length."""
import numpy as np
import pytest

import pymeshlab
from conftest import assert_unchanged, load, raises_on, shared_mesh, snapshot
from meshregrid.quality import hausdorff as symmetric_hausdorff

RIDGE_ANGLE = 30.0
# The remesher's default feature-noise suppression: ridge lines with an open end shorter than two
# elements are not features (at one element the armadillo keeps 93.9% of its edges in range).
MIN_LINE = 2.0  # x target


def min_angles(mesh: pymeshlab.Mesh) -> np.ndarray:
    """Smallest angle of every face, degrees."""
    v = mesh.vertex_matrix()
    t = v[mesh.face_matrix()]

    def angle(a, b, c):
        u, w = b - a, c - a
        return np.degrees(np.arctan2(np.linalg.norm(np.cross(u, w), axis=1), (u * w).sum(1)))

    return np.minimum.reduce([angle(t[:, 0], t[:, 1], t[:, 2]), angle(t[:, 1], t[:, 2], t[:, 0]),
                              angle(t[:, 2], t[:, 0], t[:, 1])])


def edges(mesh: pymeshlab.Mesh):
    """Undirected edges (unique) and whether every directed edge occurs once (consistent orientation)."""
    f = mesh.face_matrix()
    directed = np.concatenate([f[:, [0, 1]], f[:, [1, 2]], f[:, [2, 0]]])
    oriented = len(np.unique(directed, axis=0)) == len(directed)
    return np.unique(np.sort(directed, axis=1), axis=0), oriented


def point_segment_distance(p: np.ndarray, a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Distance of each point of p to the nearest segment (a[i], b[i])."""
    best = np.full(len(p), np.inf)
    d = b - a
    len2 = np.maximum((d * d).sum(1), 1e-300)
    for start in range(0, len(p), 256):
        q = p[start:start + 256, None, :]
        t = np.clip(((q - a[None]) * d[None]).sum(2) / len2[None], 0, 1)
        dist = np.linalg.norm(a[None] + t[..., None] * d[None] - q, axis=2)
        best[start:start + 256] = dist.min(1)
    return best


def input_ridges(name: str, min_line_length: float):
    """Corners and ridge segments of a shared mesh, from the feature filter's lines layer with the
    remesher's min_line_length (in a MeshSet of its own, so the mesh under test is not touched)."""
    ms = load(name)
    ms.compute_feature_lines_and_patches(ridge_angle=RIDGE_ANGLE, create_lines_layer=True, color_patches=False,
                                         min_line_length=pymeshlab.PureValue(min_line_length))
    m = ms.current_mesh()
    corners = m.vertex_matrix()[m.vertex_selection_array()]
    layer = ms.mesh(1)  # the lines layer is the second mesh of this fresh MeshSet
    v, e = layer.vertex_matrix(), layer.edge_matrix()
    return corners, v[e[:, 0]], v[e[:, 1]]


# Acceptance items a mesh does not meet yet at 1% / 30 degrees / min_line_length = MIN_LINE x
# target, with the measured numbers (benchmarks/remesh.md); each is asserted at the weaker bound
# given instead. None at present.
SHORTFALLS = {}


def remesh_and_compare(name):
    ms = load(name)
    src = ms.current_mesh()
    before = snapshot(src)
    diag = src.bounding_box().diagonal()
    target = 0.01 * diag
    topo_in = ms.get_topological_measures()
    corners, ridge_a, ridge_b = input_ridges(name, MIN_LINE * target)

    res = ms.meshing_advancing_front_remesh(target_length=pymeshlab.PureValue(target), ridge_angle=RIDGE_ANGLE,
                                            min_line_length=pymeshlab.PureValue(MIN_LINE * target))
    ours = ms.current_mesh_id()
    assert ours != 0 and ms.mesh_number() == 2
    assert_unchanged(before, ms.mesh(0))
    out = ms.mesh(ours)
    assert res["unmeshed_sides"] == 0
    assert res["faces"] == out.face_number()
    assert res["corners"] == len(corners)

    # Topology: manifold, oriented, same genus and boundary.
    topo = ms.get_topological_measures()
    assert topo["non_two_manifold_edges"] == 0 and topo["non_two_manifold_vertices"] == 0
    assert topo["number_holes"] == topo_in["number_holes"]
    assert topo["genus"] == topo_in["genus"]
    assert topo["connected_components_number"] == topo_in["connected_components_number"]
    e, oriented = edges(out)
    assert oriented
    # No face spans several elements (the front once chained long sides; local repair hid them).
    v_out = out.vertex_matrix()
    assert np.linalg.norm(v_out[e[:, 0]] - v_out[e[:, 1]], axis=1).max() <= 3 * target

    # Features: every input corner is an output vertex; line points lie on the input ridges.
    v = out.vertex_matrix()
    for c in corners:
        assert np.min(np.linalg.norm(v - c, axis=1)) <= 1e-12 * diag
    kind = out.vertex_custom_scalar_attribute_array("point_kind")
    on_lines = v[kind >= 1]
    assert len(on_lines) > 0
    assert point_segment_distance(on_lines, ridge_a, ridge_b).max() <= 1e-6 * diag

    # Quality against MeshLab's isotropic remesher at the same length and feature angle.
    ms.set_current_mesh(0)
    ms.generate_copy_of_current_mesh()
    iso = ms.current_mesh_id()
    ms.meshing_isotropic_explicit_remeshing(targetlen=pymeshlab.PureValue(target), featuredeg=RIDGE_ANGLE)
    a_ours, a_iso = min_angles(out), min_angles(ms.mesh(iso))
    shortfall = SHORTFALLS.get(name, {})
    if "worst_angle" in shortfall:
        assert a_ours.min() >= shortfall["worst_angle"]
    else:
        assert a_ours.min() >= a_iso.min() - 1e-9
    if "p1_angle" in shortfall:
        assert np.percentile(a_ours, 1) >= shortfall["p1_angle"]
    else:
        assert np.percentile(a_ours, 1) > np.percentile(a_iso, 1)

    # Against the input's surface: vertices no face uses (the bunny scan has 1113) are not part of it.
    ms.set_current_mesh(0)
    ms.generate_copy_of_current_mesh()
    ms.meshing_remove_unreferenced_vertices()
    surface = ms.current_mesh_id()

    def hausdorff(i):
        # Many samples: with 20k the maximum moved by ~10% between runs.
        return symmetric_hausdorff(ms, i, surface, max(20 * out.face_number(), 200000))

    if "hausdorff_rel" in shortfall:
        assert hausdorff(ours) <= shortfall["hausdorff_rel"] * diag
    else:
        assert hausdorff(ours) <= hausdorff(iso)
    lengths = np.linalg.norm(v[e[:, 0]] - v[e[:, 1]], axis=1)
    in_range = np.mean((lengths >= 0.7 * target) & (lengths <= 1.4 * target))
    assert in_range >= shortfall.get("edges_in_range", 0.95)


@pytest.mark.parametrize("name", ["cad/part.off", "cad/joint.off", "cad/fandisk.obj", "cad/blade.off",
                                  "organic/rocker-arm.obj", "organic/armadillo.off", "organic/stanford-bunny.obj"])
def test_remesh_against_isotropic(name):
    remesh_and_compare(name)


def test_strict_mode_keeps_every_30_degree_corner():
    """min_line_length = 0 keeps every ridge of the angle test: all of rocker-arm's ~1000 corners
    (most on creases shorter than the target) are output vertices; by default most of them go."""
    name = "organic/rocker-arm.obj"
    ms = load(name)
    diag = ms.current_mesh().bounding_box().diagonal()
    target = 0.01 * diag
    corners, ridge_a, ridge_b = input_ridges(name, 0.0)
    assert len(corners) > 900
    res = ms.meshing_advancing_front_remesh(target_length=pymeshlab.PureValue(target), ridge_angle=RIDGE_ANGLE,
                                            min_line_length=pymeshlab.PureValue(0.0))
    assert res["unmeshed_sides"] == 0 and res["suppressed_lines"] == 0
    assert res["corners"] == len(corners)
    out = ms.current_mesh()
    v = out.vertex_matrix()
    for c in corners:
        assert np.min(np.linalg.norm(v - c, axis=1)) <= 1e-12 * diag
    kind = out.vertex_custom_scalar_attribute_array("point_kind")
    assert point_segment_distance(v[kind >= 1], ridge_a, ridge_b).max() <= 1e-6 * diag
    assert ms.get_topological_measures()["non_two_manifold_edges"] == 0
    ms.set_current_mesh(0)
    default = ms.meshing_advancing_front_remesh(target_length=pymeshlab.PureValue(target), ridge_angle=RIDGE_ANGLE,
                                                min_line_length=pymeshlab.PureValue(MIN_LINE * target))
    assert default["suppressed_lines"] > 0 and default["corners"] < 0.6 * len(corners)


def test_bunny_with_holes_stays_manifold_with_its_holes_and_genus():
    """Regression: the open, noisy bunny scan used to come out non-manifold (a sliver patch between
    two nearly coincident ridge lines and a one-triangle island patch at a fold were covered twice,
    and small front loops stayed open). At 1% of the diagonal (about 5 s here): manifold edges and
    vertices, one component, consistent orientation, the input's 5 boundary loops and genus 0 exactly."""
    ms = load("organic/stanford-bunny.obj")
    topo_in = ms.get_topological_measures()
    target = 0.01 * ms.current_mesh().bounding_box().diagonal()
    # Strict mode (every 30-degree ridge kept): the sliver between twin lines is there at this size.
    res = ms.meshing_advancing_front_remesh(target_length=pymeshlab.PureValue(target), ridge_angle=RIDGE_ANGLE,
                                            min_line_length=pymeshlab.PureValue(0.0))
    assert res["unmeshed_sides"] == 0
    assert res["merged_lines"] >= 1
    topo = ms.get_topological_measures()
    assert topo["non_two_manifold_edges"] == 0 and topo["non_two_manifold_vertices"] == 0
    assert topo["connected_components_number"] == topo_in["connected_components_number"] == 1
    assert topo["number_holes"] == topo_in["number_holes"] == 5
    assert topo["genus"] == topo_in["genus"] == 0
    _, oriented = edges(ms.current_mesh())
    assert oriented


@pytest.mark.parametrize("ridge_angle", [179.0, 89.0])
def test_bends_that_are_not_ridges_are_covered_once(ridge_angle):
    """Regression: with few or no ridges the rocker-arm (input edges about the target length, normals
    turning by up to 110 degrees within 1.5 elements) is one patch whose front passes itself at bends
    its normal filters cannot see; faces were laid over faces already made: 7.9x the input area at
    179 degrees and 4.8x at 89, thousands of open sides. Measured now: area 0.991, 7 open sides,
    Hausdorff 0.5% of the diagonal."""
    ms = load("organic/rocker-arm.obj")
    diag = ms.current_mesh().bounding_box().diagonal()
    area_in = ms.get_geometric_measures()["surface_area"]
    res = ms.meshing_advancing_front_remesh(target_length=pymeshlab.PureValue(0.01 * diag), ridge_angle=ridge_angle)
    area = ms.get_geometric_measures()["surface_area"]
    assert 0.97 <= area / area_in <= 1.02
    assert res["unmeshed_sides"] <= 20
    assert ms.get_topological_measures()["non_two_manifold_edges"] == 0
    assert symmetric_hausdorff(ms, 1, 0, 50000) <= 0.01 * diag


@pytest.mark.parametrize("line_source", [False, True])
def test_size_source_layer_points_and_lines(line_source):
    """A source layer's vertices are point sources and its edges line sources, the size (vertex
    quality) interpolated along each edge. The segment from (-1,0,1) to (1,0,1) touches the unit
    sphere at its top only: as two point sources its ends (0.41 from the sphere) barely matter
    (graded size 0.02 + 0.3 x 0.41 = 0.14 against the target 0.15), as a line source it refines the
    top to its interpolated size (0.03 at x = 0). Measured: 0.033-0.035 near the top with the
    edge, 0.17 without."""
    ms = pymeshlab.MeshSet()
    ms.create_sphere(subdiv=5)
    ends = np.array([[-1.0, 0, 1.0], [1.0, 0, 1.0]])
    extra = dict(edge_matrix=np.array([[0, 1]], dtype=np.int32)) if line_source else {}
    ms.add_mesh(pymeshlab.Mesh(ends, v_scalar_array=np.array([0.02, 0.04]), **extra), "source")
    ms.set_current_mesh(0)
    res = ms.meshing_advancing_front_remesh(target_length=pymeshlab.PureValue(0.15), use_size_source=True,
                                            size_source=1, gradation=1.3)
    assert res["unmeshed_sides"] == 0
    m = ms.current_mesh()
    v, f = m.vertex_matrix(), m.face_matrix()
    e, _ = edges(m)
    mid, lengths = v[e].mean(1), np.linalg.norm(v[e[:, 0]] - v[e[:, 1]], axis=1)
    for x in (-0.1, 0.0, 0.1):
        near = np.linalg.norm(mid - [x, 0, 1], axis=1) < 0.08
        assert near.any()
        wanted = 0.02 + 0.02 * (x + 1) / 2
        if line_source:
            assert 0.7 * wanted <= lengths[near].mean() <= 1.4 * wanted
        else:
            assert lengths[near].mean() >= 0.1
    far = mid[:, 2] < -0.5
    assert 0.7 * 0.15 <= lengths[far].mean() <= 1.4 * 0.15


def test_blade_thin_rims_are_meshed_and_keep_topology():
    """Regression: cad/blade.off is a thin plate whose two rims are strips 0.033 wide (2.5% of the
    1% target) between ridge lines; no front layer fits there, they were left unmeshed (410 front
    sides) and the output fell into two components. They now get one layer of faces between their
    lines: manifold, one component, the input's 2 boundary loops and genus 0 exactly. The points of
    one line of a rim are staggered by 0.28 of a segment against the other's (right across, as
    before, the faces had 1.09 degrees): measured 1.51 degrees, MeshLab's isotropic remesher 1.0."""
    ms = load("cad/blade.off")
    topo_in = ms.get_topological_measures()
    target = 0.01 * ms.current_mesh().bounding_box().diagonal()
    res = ms.meshing_advancing_front_remesh(target_length=pymeshlab.PureValue(target), ridge_angle=RIDGE_ANGLE)
    assert res["unmeshed_sides"] == 0
    assert res["thin_patches"] == 2
    topo = ms.get_topological_measures()
    assert topo["non_two_manifold_edges"] == 0 and topo["non_two_manifold_vertices"] == 0
    assert topo["connected_components_number"] == topo_in["connected_components_number"] == 1
    assert topo["number_holes"] == topo_in["number_holes"] == 2
    assert topo["genus"] == topo_in["genus"] == 0
    _, oriented = edges(ms.current_mesh())
    assert oriented
    assert min_angles(ms.current_mesh()).min() >= 1.5


def test_thin_plate_rims_get_one_layer_between_their_ridges():
    """A 100 x 50 x 0.1 plate at target 2: the four rims (0.1 wide, a twentieth of the size) are
    thin strips meshed by one layer of faces between their ridges; the plate stays closed, genus 0,
    and the worst angle is that of one layer whose points are staggered by 0.28 of the line spacing,
    atan(0.1 / (0.72 x 2)) = 3.97 degrees (right across each other they would give 2.86)."""
    ms = pymeshlab.MeshSet()
    ms.create_cube()  # side 2, centred
    cube = ms.current_mesh()
    ms.add_mesh(pymeshlab.Mesh(cube.vertex_matrix() * np.array([50.0, 25.0, 0.05]), cube.face_matrix()))
    res = ms.meshing_advancing_front_remesh(target_length=pymeshlab.PureValue(2.0))
    assert res["unmeshed_sides"] == 0 and res["thin_patches"] == 4 and res["corners"] == 8
    topo = ms.get_topological_measures()
    assert topo["non_two_manifold_edges"] == 0 and topo["non_two_manifold_vertices"] == 0
    assert topo["boundary_edges"] == 0 and topo["genus"] == 0 and topo["connected_components_number"] == 1
    _, oriented = edges(ms.current_mesh())
    assert oriented
    assert min_angles(ms.current_mesh()).min() >= np.degrees(np.arctan(0.1 / (0.72 * 2.0))) * 0.95


def cad_cylinder(radius=10.0, height=200.0, segments=500):
    """A cylinder as CAD exports it: each side triangle spans the full height, caps fanned from one rim vertex."""
    t = 2 * np.pi * np.arange(segments) / segments
    ring = np.stack([radius * np.cos(t), radius * np.sin(t)], 1)
    v = np.concatenate([np.c_[ring, np.zeros(segments)], np.c_[ring, np.full(segments, height)]])
    f = []
    for i in range(segments):
        j = (i + 1) % segments
        f += [[i, j, segments + j], [i, segments + j, segments + i]]
    for i in range(1, segments - 1):
        f.append([0, i + 1, i])                                      # bottom, facing -z
        f.append([segments, segments + i, segments + i + 1])        # top, facing +z
    return pymeshlab.Mesh(v, np.array(f))


def test_sliver_cylinder_keeps_two_circular_ridges_and_30_degrees():
    ms = pymeshlab.MeshSet()
    ms.add_mesh(cad_cylinder())
    res = ms.meshing_advancing_front_remesh(target_length=pymeshlab.PureValue(2.0))
    assert res["unmeshed_sides"] == 0
    assert res["corners"] == 0 and res["lines"] == 2
    out = ms.current_mesh()
    assert min_angles(out).min() >= 30.0
    # The output's own ridges are exactly the two circles: no spurious feature edges.
    feat = ms.compute_feature_lines_and_patches(ridge_angle=RIDGE_ANGLE, color_patches=False)
    assert feat["lines"] == 2 and feat["corners"] == 0
    assert feat["ridge_edges"] == res["feature_edges"]
    # Line points lie on the input's rim polygons (chords of the circles).
    v = out.vertex_matrix()
    kind = out.vertex_custom_scalar_attribute_array("point_kind")
    rim = v[kind >= 1]
    src = ms.mesh(0).vertex_matrix()
    n = len(src) // 2
    nxt = np.r_[np.arange(1, n), 0]
    a = np.concatenate([src[:n], src[n:]])
    b = np.concatenate([src[:n][nxt], src[n:][nxt]])
    assert point_segment_distance(rim, a, b).max() <= 1e-9


def test_relax_wedges_takes_fandisk_to_30_degrees_where_two_ridges_leave_a_corner_at_19():
    # fandisk at 1%: one face fills a 19.38-degree wedge between two of its ridges, every other
    # face has 30.07. Relaxed, the ridges share their first segment there: no wedge tip is left,
    # every face has 30.07 degrees, and the distance to the input goes from 0.00102 to 0.00117 of
    # the diagonal (the ridges' detour at the tip).
    kept = load("cad/fandisk.obj")
    plain = kept.meshing_advancing_front_remesh(target_length=pymeshlab.PercentageValue(1.0))
    assert plain["wedge_tips"] == 1 and plain["min_wedge_angle"] == pytest.approx(19.38, abs=0.01)
    ms = load("cad/fandisk.obj")
    res = ms.meshing_advancing_front_remesh(target_length=pymeshlab.PercentageValue(1.0), relax_wedges=True)
    assert res["relaxed_wedges"] == 1 and res["wedge_tips"] == 0 and res["unmeshed_sides"] == 0
    assert res["min_angle"] >= 30.0 and min_angles(ms.current_mesh()).min() >= 30.0
    assert res["missing_feature_edges"] == 0
    assert res["hausdorff_rel"] <= 1.5e-3 and res["hausdorff_rel"] <= plain["hausdorff_rel"] * 1.25
    topo = ms.get_topological_measures()
    assert topo["is_mesh_two_manifold"] and topo["boundary_edges"] == kept.get_topological_measures()["boundary_edges"]


def narrow_prism(apex_deg, length=10.0, height=3.0):
    """A prism over an isosceles triangle with the given apex angle: its top and bottom faces
    have a corner where two ridges leave at that angle."""
    h, w = length * np.cos(np.radians(apex_deg / 2)), length * np.sin(np.radians(apex_deg / 2))
    tri = np.array([[0, 0], [h, w], [h, -w]])
    v = np.concatenate([np.c_[tri, np.zeros(3)], np.c_[tri, np.full(3, height)]])
    f = [[0, 2, 1], [3, 4, 5], [0, 1, 4], [0, 4, 3], [1, 2, 5], [1, 5, 4], [2, 0, 3], [2, 3, 5]]
    return pymeshlab.Mesh(v, np.array(f))


@pytest.mark.parametrize("apex", [10.0, 20.0])
def test_wedges_between_ridges_are_measured_apart_from_the_rest(apex):
    # The apex corners of the top and bottom faces: one face fills each wedge, its angle there is
    # the apex's (no mesh keeping the ridges can do better). The dictionary says so, and every
    # other corner is measured on its own: at 5% measured 14.3 (10-degree apex) and 31.4 degrees.
    ms = pymeshlab.MeshSet()
    ms.add_mesh(narrow_prism(apex))
    res = ms.meshing_advancing_front_remesh(target_length=pymeshlab.PercentageValue(5.0))
    assert res["unmeshed_sides"] == 0
    assert res["wedge_tips"] == 2
    assert res["min_wedge_angle"] == pytest.approx(apex, abs=1e-6)
    assert res["min_angle_off_wedges"] > apex
    assert min_angles(ms.current_mesh()).min() == pytest.approx(res["min_angle"], abs=1e-9)
    assert res["min_angle"] == pytest.approx(min(res["min_wedge_angle"], res["min_angle_off_wedges"]), abs=1e-9)
    # A wide apex has no wedge tip.
    ms.add_mesh(narrow_prism(60.0))
    wide = ms.meshing_advancing_front_remesh(target_length=pymeshlab.PercentageValue(5.0))
    assert wide["wedge_tips"] == 0 and wide["min_wedge_angle"] == 180.0
    assert wide["min_angle_off_wedges"] == pytest.approx(wide["min_angle"], abs=1e-9)


def test_recovery_modes_on_a_coarse_sphere():
    ms = pymeshlab.MeshSet()
    ms.create_sphere(subdiv=1)  # icosphere of radius 1, 80 faces
    src = ms.current_mesh().vertex_matrix().copy()
    error = {}
    for mode, label in enumerate(["linear", "closest", "quadratic", "cubic"]):
        ms.set_current_mesh(0)
        res = ms.meshing_advancing_front_remesh(target_length=pymeshlab.PureValue(0.2), recovery=mode)
        assert res["unmeshed_sides"] == 0
        v = ms.current_mesh().vertex_matrix()
        error[label] = np.abs(np.linalg.norm(v, axis=1) - 1).mean()
        if label == "closest":
            at_input = [np.min(np.linalg.norm(src - p, axis=1)) < 1e-12 for p in v]
            assert sum(at_input) >= 0.9 * len(src)  # nearly every input vertex got an output point
        assert ms.get_topological_measures()["non_two_manifold_edges"] == 0
    assert error["quadratic"] < 0.5 * error["linear"]
    assert error["cubic"] < 0.5 * error["linear"]


def test_bad_input_raises_and_changes_nothing():
    ms = pymeshlab.MeshSet()
    ms.create_cube()
    before = snapshot(ms.current_mesh())
    diag = ms.current_mesh().bounding_box().diagonal()
    with raises_on(ms, "target_length must be > 0"):
        ms.meshing_advancing_front_remesh(target_length=pymeshlab.PureValue(0.0))
    with raises_on(ms, "larger than the model"):
        ms.meshing_advancing_front_remesh(target_length=pymeshlab.PureValue(2 * diag))
    with raises_on(ms, "min_line_length must be >= 0"):
        ms.meshing_advancing_front_remesh(min_line_length=pymeshlab.PureValue(-1.0))
    with raises_on(ms, "min_line_length must be finite"):
        ms.meshing_advancing_front_remesh(min_line_length=pymeshlab.PureValue(float("nan")))
    source = pymeshlab.Mesh(np.array([[0, 0, 0], [1, 1, 1]], float), edge_matrix=np.array([[0, 1]], dtype=np.int32),
                            v_scalar_array=np.array([np.nan, 1.0]))
    ms.add_mesh(source, "bad source")
    ms.set_current_mesh(0)
    with raises_on(ms, "quality \\(size\\) > 0"):
        ms.meshing_advancing_front_remesh(use_size_source=True, size_source=1)
    assert ms.mesh_number() == 2
    ms.set_current_mesh(0)
    assert_unchanged(before, ms.current_mesh())

    cloud = pymeshlab.MeshSet()
    cloud.add_mesh(pymeshlab.Mesh(np.random.default_rng(1).random((20, 3))))
    with raises_on(cloud, "no faces|point cloud"):
        cloud.meshing_advancing_front_remesh()

    nan = pymeshlab.MeshSet()
    v = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [np.nan, 0, 1]], float)
    nan.add_mesh(pymeshlab.Mesh(v, np.array([[0, 1, 2], [0, 2, 3]])))
    with raises_on(nan, "finite|NaN"):
        nan.meshing_advancing_front_remesh(target_length=pymeshlab.PureValue(0.1))

    # A double layer (faces repeated with reversed orientation) made every edge non-manifold
    # and the fronts of thousands of two-face patches ran for minutes (a fuzzed bunny at 0.5%:
    # 281 s, 1007 patches left unmeshed); it is refused up front with the repair filter's name.
    double = pymeshlab.MeshSet()
    double.create_cube()
    cube = double.current_mesh()
    f = cube.face_matrix()
    double.add_mesh(pymeshlab.Mesh(cube.vertex_matrix(), np.concatenate([f, f[:3, ::-1]])), "double layer")
    before_double = snapshot(double.current_mesh())
    with raises_on(double, "3 duplicate faces.*Remove Duplicate Faces"):
        double.meshing_advancing_front_remesh()
    assert double.mesh_number() == 2
    assert_unchanged(before_double, double.current_mesh())

    # Every face with a repeated corner (no area anywhere): quadratic recovery wrote NaN points
    # (scripts/fuzz_filters.py seed 186); it is refused up front.
    flat = pymeshlab.MeshSet()
    flat.create_cube()
    f = flat.current_mesh().face_matrix().copy()
    f[:, 1] = f[:, 0]
    flat.add_mesh(pymeshlab.Mesh(flat.current_mesh().vertex_matrix(), f), "degenerate")
    before_flat = snapshot(flat.current_mesh())
    with raises_on(flat, "no face of nonzero area"):
        flat.meshing_advancing_front_remesh(recovery=2)
    assert flat.mesh_number() == 2
    assert_unchanged(before_flat, flat.current_mesh())


def test_bug_a_surface_flattened_onto_itself_with_nothing_meshed_is_an_error():
    # blade.off with every y set to 0 (scripts/fuzz_remesh.py seed 131): its two sides lie on
    # each other and every front stopped open, so the filter added an empty layer and said so
    # only in the dictionary (16 open sides, 1 unmeshed patch). Now it is an error, and the
    # document keeps no empty layer. Flattened across x it still meshes part (111 faces).
    src = load("cad/blade.off")
    v, f = src.current_mesh().vertex_matrix().copy(), src.current_mesh().face_matrix()
    diag = src.current_mesh().bounding_box().diagonal()
    v[:, 1] = 0
    ms = pymeshlab.MeshSet()
    ms.add_mesh(pymeshlab.Mesh(v, f))
    before = snapshot(ms.current_mesh())
    with raises_on(ms, "no patch could be meshed \\(16 front sides stayed open\\).*folded or flat"):
        ms.meshing_advancing_front_remesh(target_length=pymeshlab.PureValue(0.02 * diag), ridge_angle=20.0)
    assert ms.mesh_number() == 1
    assert_unchanged(before, ms.current_mesh())


def test_input_with_flipped_faces_is_remeshed_as_if_it_were_oriented():
    # Every other face flipped (a careless export): the host-face search compares normals and the
    # fronts take their direction from the faces; a fuzzed bunny took 88 s and left sides open.
    # The core now works on a coherently oriented copy. The copy flips a face by swapping its
    # corners 1 and 2, so faces flipped that way come back exactly: the very same output.
    src = load("cad/fandisk.obj")
    v, f = src.current_mesh().vertex_matrix(), src.current_mesh().face_matrix()
    flipped = f.copy()
    flipped[::2] = flipped[::2][:, [0, 2, 1]]
    results = []
    for faces in (f, flipped):
        ms = pymeshlab.MeshSet()
        ms.add_mesh(pymeshlab.Mesh(v, faces))
        before = snapshot(ms.current_mesh())
        r = ms.meshing_advancing_front_remesh(target_length=pymeshlab.PercentageValue(5.0))
        assert_unchanged(before, ms.mesh(0))
        out = ms.current_mesh()
        assert r["unmeshed_sides"] == 0 and edges(out)[1]
        results.append((out.vertex_matrix().copy(), out.face_matrix().copy()))
    assert np.array_equal(results[0][0], results[1][0]) and np.array_equal(results[0][1], results[1][1])


def test_bug_fandisk_far_from_the_origin_is_meshed_as_near_it():
    # fandisk moved 1e5 of its diagonals away (coordinates near 1e6, as in UTM frames) left a
    # patch unmeshed, two sides open and a 10.3 degree face: the tolerances scaled by the element
    # size met rounding noise. The core now shifts such an input next to the origin, exactly, so
    # the input's corners come back bit for bit.
    src = load("cad/fandisk.obj")
    v, f = src.current_mesh().vertex_matrix(), src.current_mesh().face_matrix()
    diagonal = np.linalg.norm(v.max(0) - v.min(0))
    far = v + np.array([1.3, -0.7, 0.9]) * 1e5 * diagonal
    ms = pymeshlab.MeshSet()
    ms.add_mesh(pymeshlab.Mesh(far, f))
    before = snapshot(ms.current_mesh())
    r = ms.meshing_advancing_front_remesh()
    assert_unchanged(before, ms.mesh(0))
    assert r["unmeshed_sides"] == 0 and r["unmeshed_patches"] == 0 and r["retried_patches"] == 0
    assert r["min_angle"] > 19.0  # 19.38 near the origin, 10.3 before the shift
    assert r["hausdorff_rel"] < 1.5e-3  # 1.0e-3 near the origin
    out = ms.current_mesh()
    topo = ms.get_topological_measures()
    assert topo["boundary_edges"] == 0 and topo["is_mesh_two_manifold"] and edges(out)[1]
    corners = out.vertex_matrix()[out.vertex_custom_scalar_attribute_array("point_kind") == 2]
    assert len(corners) == r["corners"] == 25
    kept = {tuple(p) for p in far}
    assert all(tuple(c) in kept for c in corners)  # bit for bit


@pytest.mark.parametrize("percent,at_least", [(1.0, 15.0), (2.0, 8.0)])
def test_crumples_of_a_cad_export_are_dropped_and_its_angles_rise(percent, at_least):
    # healing/ALSTOM_TEST4.off has six faces turned over against their neighbours (crumples,
    # found by stage 1 at 0.5-2%). Kept as patches, each was meshed as it stood: the smallest
    # angle was 2.33 degrees at 1% and 0.28 at 2%. Dropped: 19.2 and 10.3 (bounds 15 and 8).
    ms = load("healing/ALSTOM_TEST4.off")
    features = ms.compute_feature_lines_and_patches(min_line_length=pymeshlab.PercentageValue(percent))
    assert features["suppressed_crumples"] >= 1
    res = ms.meshing_advancing_front_remesh(target_length=pymeshlab.PercentageValue(percent))
    assert res["unmeshed_sides"] == 0 and res["non_manifold_points"] == 0 and not res["kept_crumples"]
    assert res["min_angle"] >= at_least
    assert ms.get_topological_measures()["is_mesh_two_manifold"]


def test_boeing_patches_at_half_a_percent_are_all_meshed_and_two_manifold():
    # healing/boeing.off (122 patches with duplicated seams) at 0.5%. Before stop 45 the regrid
    # had 30 non-manifold points and 4679 open sides in 26 patches, a face of 0 degrees and a
    # Hausdorff distance of 0.059 of the diagonal. Since fronts take a line or corner point only
    # within the angle still to mesh there, and a fan closed round such a point counts as a
    # pinch for local repair (docs/remesh.md step 4): none open or pinched, 7.1 degrees, 0.0013
    # (bounds 5 and 0.005).
    ms = load("healing/boeing.off")
    res = ms.meshing_advancing_front_remesh(target_length=pymeshlab.PercentageValue(0.5))
    assert res["unmeshed_sides"] == 0 and res["unmeshed_patches"] == 0 and res["non_manifold_points"] == 0
    assert ms.get_topological_measures()["is_mesh_two_manifold"]
    assert res["min_angle"] >= 5.0
    assert res["hausdorff_rel"] < 0.005


def test_damaged_input_that_no_front_can_close_returns_and_reports_it():
    # Fuzzing found this: blade.off with every 30th vertex (random, seed 3) moved onto the next
    # one: about 150 zero-area faces and folds. At 5% and 20 degrees 1500 front sides of one
    # patch never close and every step looked at all of them, so the filter ran for more than a
    # quarter of an hour. Each front's work is now bounded as well as its steps (the benchmark
    # meshes use at most 1/60 of the bound): the filter returns with the open sides reported.
    # Measured: 975 faces and 520 open sides (2153 and 1996 while crumples, turned-over faces the
    # damage makes, stayed patches of their own; merged, fewer patches fail, but larger ones).
    ms = load("cad/blade.off")
    v = ms.current_mesh().vertex_matrix().copy()
    f = ms.current_mesh().face_matrix()
    k = np.random.default_rng(3).choice(len(v), size=len(v) // 30)
    v[k] = v[(k + 1) % len(v)]
    damaged = pymeshlab.MeshSet()
    damaged.add_mesh(pymeshlab.Mesh(v, f), "damaged blade")
    before = snapshot(damaged.current_mesh())
    res = damaged.meshing_advancing_front_remesh(target_length=pymeshlab.PercentageValue(5.0), ridge_angle=20.0)
    assert res["unmeshed_sides"] > 0 and res["unmeshed_patches"] > 0
    # Patches whose front stopped at its bound but that the last resort closed are not unmeshed
    # (they were counted so before): measured 9 stopped, 2 of them open.
    assert res["unmeshed_patches"] < res["bounded_patches"] <= res["patches"]
    assert damaged.mesh_number() == 2 and damaged.current_mesh().face_number() > 500
    assert_unchanged(before, damaged.mesh(0))


def test_pipeline_and_cli(tmp_path):
    from meshregrid import cli, pipeline_remesh

    ms = load("cad/part.off")
    res = pipeline_remesh.remesh(ms, target_percent=3.0)
    assert res["unmeshed_sides"] == 0 and res["features"]["patches"] == res["patches"]
    assert ms.mesh_number() == 2 and ms.current_mesh().face_number() == res["faces"]
    out = tmp_path / "part_remeshed.ply"
    rc = cli.main(["remesh", str(shared_mesh("cad/part.off")), str(out), "--target-percent", "3"])
    assert rc == 0
    back = pymeshlab.MeshSet()
    back.load_new_mesh(str(out))
    assert back.current_mesh().face_number() == res["faces"]
