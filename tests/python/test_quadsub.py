"""Regression tests of meshing_surface_subdivision_interpolatory_quad through PyMeshLab."""
import collections
import itertools

import numpy as np
import pymeshlab
import pytest

from conftest import assert_unchanged, raises_on, shared_mesh, snapshot

QUAD_MESHES = ["quad/spot_quadrangulated.obj", "quad/spot_control_mesh.obj", "quad/quadknot.obj",
               "quad/torus_quad.off", "quad/inspired_mesh_quads_Conjugate.off"]


def load_polygons(relative):
    """Loads a polygon mesh; OFF files are parsed here (PyMeshLab 2025.07 crashes on one of them)."""
    path = shared_mesh(relative)
    ms = pymeshlab.MeshSet()
    if path.suffix == ".off":
        tokens = [line.split("#")[0] for line in path.read_text().splitlines()]
        words = " ".join(tokens).split()
        assert words[0] == "OFF"
        nv, nf = int(words[1]), int(words[2])
        values = words[4:]
        v = np.array(values[:3 * nv], dtype=float).reshape(nv, 3)
        faces, k = [], 3 * nv
        for _ in range(nf):
            n = int(values[k])
            faces.append(np.array(values[k + 1:k + 1 + n], dtype=np.uint32))
            k += 1 + n
        ms.add_mesh(pymeshlab.Mesh(vertex_matrix=v, face_list_of_indices=faces))
    else:
        ms.load_new_mesh(str(path))
    return ms


def polygon_sizes(mesh):
    return collections.Counter(len(p) for p in mesh.polygonal_face_list())


def level_zero_quads(polygons):
    """Quads before the first step: an n-gon (n != 4) gives n; so that no midpoint hangs, every quad
    on a strip leaving a split side gives 2, and a quad crossed by two strips gives 4."""
    polygons = [list(p) for p in polygons]
    edge = lambda a, b: (min(a, b), max(a, b))
    quads_on = collections.defaultdict(list)
    for p in polygons:
        if len(p) == 4:
            for s in range(4):
                quads_on[edge(p[s], p[(s + 1) % 4])].append((p, s))
    cut = {edge(p[k], p[(k + 1) % len(p)]) for p in polygons if len(p) != 4 for k in range(len(p))}
    work = list(cut)
    while work:
        for p, s in quads_on[work.pop()]:
            opposite = edge(p[(s + 2) % 4], p[(s + 3) % 4])
            if opposite not in cut:
                cut.add(opposite)
                work.append(opposite)
    count = 0
    for p in polygons:
        if len(p) != 4:
            count += len(p)
        else:
            count += (1 + (edge(p[0], p[1]) in cut)) * (1 + (edge(p[1], p[2]) in cut))
    return count


@pytest.mark.parametrize("name", QUAD_MESHES)
def test_every_input_vertex_is_kept_bit_for_bit_and_the_output_is_quads(name):
    ms = load_polygons(name)
    before = snapshot(ms.current_mesh())
    r = ms.meshing_surface_subdivision_interpolatory_quad(iterations=1)
    assert_unchanged(before, ms.mesh(0))  # the input layer is untouched
    out = ms.current_mesh()
    assert ms.mesh_number() == 2
    v_in = before[0]
    np.testing.assert_array_equal(out.vertex_matrix()[:len(v_in)], v_in)
    quads_in = level_zero_quads(ms.mesh(0).polygonal_face_list())
    assert r["faces_out"] == 4 * quads_in
    assert polygon_sizes(out) == {4: r["faces_out"]}
    assert np.isfinite(out.vertex_matrix()).all()
    assert (out.face_custom_scalar_attribute_array("subdivision_level") == 1).all()
    assert r["faces_refined_level_0"] == quads_in and r["triangles_out"] == 0


@pytest.mark.parametrize("name", ["quad/quadknot.obj", "quad/torus_quad.off"])
def test_closed_genus_one_nets_stay_closed_with_the_same_genus(name):
    ms = load_polygons(name)
    ms.meshing_surface_subdivision_interpolatory_quad(iterations=2)
    topo = ms.get_topological_measures()
    assert topo["boundary_edges"] == 0
    assert topo["is_mesh_two_manifold"]
    assert topo["genus"] == 1


@pytest.mark.parametrize("adaptive", [0, 1, 2])
def test_quad_dominant_mesh_has_no_crack_beside_its_split_pentagons_and_triangles(adaptive):
    # spot_control_mesh has 16 pentagons and 4 triangles among 160 quads: splitting only those
    # left hanging midpoints on the sides of their quad neighbours (324 boundary edges).
    ms = load_polygons("quad/spot_control_mesh.obj")
    assert set(polygon_sizes(ms.current_mesh())) == {3, 4, 5}
    ms.compute_selection_by_condition_per_face(condselect="x0 > 0")
    ms.meshing_surface_subdivision_interpolatory_quad(iterations=2, adaptive=adaptive)
    topo = ms.get_topological_measures()
    assert topo["boundary_edges"] == 0 and topo["is_mesh_two_manifold"] and topo["genus"] == 0
    assert face_levels_are_balanced(ms.current_mesh()) <= 1


def test_extraordinary_vertices_are_counted_on_spot():
    ms = load_polygons("quad/spot_control_mesh.obj")
    r = ms.meshing_surface_subdivision_interpolatory_quad()
    assert r["extraordinary_vertices"] > 0
    assert r["vertices_in"] == 188 and r["faces_in"] == 180


def test_saving_to_obj_keeps_quads(tmp_path):
    ms = load_polygons("quad/torus_quad.off")
    ms.meshing_surface_subdivision_interpolatory_quad(iterations=1)
    path = tmp_path / "torus.obj"
    ms.save_current_mesh(str(path))
    again = pymeshlab.MeshSet()
    again.load_new_mesh(str(path))
    assert polygon_sizes(again.current_mesh()) == {4: 100}


def test_cubic_precision_through_pymeshlab():
    # a regular planar grid sampling a bicubic: new vertices away from the border lie on it
    n = 8
    xs = np.linspace(0, 1, n + 1)
    f = lambda x, y: 0.5 * x ** 3 - x * y * y + 0.25 * y ** 3
    v = np.array([[x, y, f(x, y)] for y in xs for x in xs])
    faces = [np.array([j * (n + 1) + i, j * (n + 1) + i + 1, (j + 1) * (n + 1) + i + 1, (j + 1) * (n + 1) + i],
                      dtype=np.uint32) for j in range(n) for i in range(n)]
    ms = pymeshlab.MeshSet()
    ms.add_mesh(pymeshlab.Mesh(vertex_matrix=v, face_list_of_indices=faces))
    ms.meshing_surface_subdivision_interpolatory_quad(w=1.0)
    p = ms.current_mesh().vertex_matrix()
    inner = (p[:, 0] >= 2 / n - 1e-9) & (p[:, 0] <= 1 - 2 / n + 1e-9) & (p[:, 1] >= 2 / n - 1e-9) & (p[:, 1] <= 1 - 2 / n + 1e-9)
    assert inner.sum() == (2 * (n - 4) + 1) ** 2
    np.testing.assert_allclose(p[inner, 2], f(p[inner, 0], p[inner, 1]), atol=1e-12)


@pytest.mark.parametrize("bad", [dict(w=1.3), dict(w=-0.01), dict(iterations=0)])
def test_bad_parameters_raise_and_leave_the_mesh(bad):
    ms = load_polygons("quad/torus_quad.off")
    before = snapshot(ms.current_mesh())
    with raises_on(ms, "must lie"):
        ms.meshing_surface_subdivision_interpolatory_quad(**bad)
    assert ms.mesh_number() == 1
    assert_unchanged(before, ms.current_mesh())


def test_point_cloud_raises():
    ms = pymeshlab.MeshSet()
    ms.add_mesh(pymeshlab.Mesh(vertex_matrix=np.random.default_rng(0).random((20, 3))))
    with raises_on(ms, "no faces"):
        ms.meshing_surface_subdivision_interpolatory_quad()


def test_convergence_rate_is_fourth_order_on_a_smooth_height_field():
    import sys
    from conftest import REPO
    sys.path.insert(0, str(REPO / "scripts"))
    import convergence_quad
    l1 = [convergence_quad.errors("height field", n)[0] for n in (8, 16, 32)]
    # cubic precision on regular grids: one step's error falls like h^4 (ratio 16 per halving)
    assert l1[0] / l1[1] > 14 and l1[1] / l1[2] > 14


# --- adaptive refinement ---------------------------------------------------------------------

REGION = "(x > 0.2) && (z > 0.6)"  # a patch on spot's back


def select_region(ms, condition=REGION):
    """Selects the triangles touching the region; returns which quads (polygonal_face_list order)
    have a selected triangle, the filter's rule for a selected polygon."""
    ms.compute_selection_by_condition_per_vertex(condselect=condition)
    ms.compute_selection_transfer_vertex_to_face(inclusive=True)
    mesh = ms.current_mesh()
    selected_triangle = {frozenset(f): s for f, s in zip(mesh.face_matrix(), mesh.face_selection_array())}
    quads = mesh.polygonal_face_list()
    return np.array([any(selected_triangle.get(frozenset(t), False) for t in itertools.combinations(q, 3))
                     for q in quads])


def quad_edges(quad):
    return [tuple(sorted((quad[k], quad[(k + 1) % 4]))) for k in range(4)]


def expected_single_level_faces(quads, selected):
    """Quads and triangles after one adaptive step, from the templates: a split face gives 4 quads; an
    unsplit face with hanging points on h sides gives h=1: 2 quads + 1 triangle, h=2 adjacent: 3 quads,
    h=2 opposite: 2 quads, h=3: 3 quads + 1 triangle; a face with 4 split neighbours is split too."""
    faces_of = collections.defaultdict(list)
    for i, q in enumerate(quads):
        for e in quad_edges(q):
            faces_of[e].append(i)
    split = set(np.flatnonzero(selected))
    hanging = lambda i: [any(g in split for g in faces_of[e] if g != i) for e in quad_edges(quads[i])]
    while True:
        closed = {i for i in range(len(quads)) if i not in split and all(hanging(i))}
        if not closed:
            break
        split |= closed
    n_quads, n_tris = 4 * len(split), 0
    for i in range(len(quads)):
        if i in split:
            continue
        h = hanging(i)
        count = sum(h)
        opposite = count == 2 and h[0] == h[2]
        n_quads += {0: 1, 1: 2, 2: 2 if opposite else 3, 3: 3}[count]
        n_tris += count in (1, 3)
    return n_quads, n_tris


def face_levels_are_balanced(mesh):
    """Largest level difference between two faces sharing an edge (faux diagonals included)."""
    level = mesh.face_custom_scalar_attribute_array("subdivision_level")
    faces = mesh.face_matrix()
    edges = np.sort(np.concatenate([faces[:, [0, 1]], faces[:, [1, 2]], faces[:, [2, 0]]]), axis=1)
    owner = np.tile(np.arange(len(faces)), 3)
    order = np.lexsort((edges[:, 1], edges[:, 0]))
    edges, owner = edges[order], owner[order]
    same = (edges[1:] == edges[:-1]).all(axis=1)
    assert same.sum() * 2 == len(edges)  # closed: every edge has exactly two faces
    return np.abs(level[owner[1:][same]] - level[owner[:-1][same]]).max()


def polygon_keys(polygons):
    """Polygons as rotation-free keys (starting at the smallest index)."""
    keys = set()
    for p in polygons:
        p = list(p)
        k = p.index(min(p))
        keys.add(tuple(p[k:] + p[:k]))
    return keys


def test_one_adaptive_step_on_a_selected_region_gives_the_template_face_counts():
    ms = load_polygons("quad/spot_quadrangulated.obj")
    quads = [list(p) for p in ms.current_mesh().polygonal_face_list()]
    assert {len(q) for q in quads} == {4}
    selected = select_region(ms)
    assert 50 < selected.sum() < len(quads) / 4
    r = ms.meshing_surface_subdivision_interpolatory_quad(iterations=1, adaptive=1)
    n_quads, n_tris = expected_single_level_faces(quads, selected)
    assert (r["quads_out"], r["triangles_out"]) == (n_quads, n_tris)
    assert r["faces_refined_level_0"] >= selected.sum() and r["balance_refinements"] == 0
    assert polygon_sizes(ms.current_mesh()) == {4: n_quads, 3: n_tris}


def test_refining_a_selected_region_twice_leaves_no_crack_and_stays_balanced():
    ms = load_polygons("quad/spot_quadrangulated.obj")
    v_in = ms.current_mesh().vertex_matrix().copy()
    quads_in = [list(p) for p in ms.current_mesh().polygonal_face_list()]
    select_region(ms)
    r = ms.meshing_surface_subdivision_interpolatory_quad(iterations=2, adaptive=1)
    out = ms.current_mesh()
    topo = ms.get_topological_measures()
    assert topo["boundary_edges"] == 0 and topo["is_mesh_two_manifold"] and topo["genus"] == 0
    assert topo["unreferenced_vertices"] == 0
    assert face_levels_are_balanced(out) == 1
    level = out.face_custom_scalar_attribute_array("subdivision_level")
    assert level.max() == r["levels"] == 2
    assert r["balance_refinements"] > 0
    # interpolation: the input vertices, bit for bit, at their indices
    np.testing.assert_array_equal(out.vertex_matrix()[:len(v_in)], v_in)
    # every vertex is a vertex of the uniform scheme at level 2 (same rules, same points)
    uniform = load_polygons("quad/spot_quadrangulated.obj")
    uniform.meshing_surface_subdivision_interpolatory_quad(iterations=2)
    on_uniform = {tuple(p) for p in uniform.current_mesh().vertex_matrix()}
    assert all(tuple(p) in on_uniform for p in out.vertex_matrix())
    # far from the region the input quads come back as they were; level 2 stays near the region
    far = [q for q in quads_in if (v_in[q, 2] < 0.3).all()]
    assert len(far) > len(quads_in) / 3
    assert polygon_keys(far) <= polygon_keys(out.polygonal_face_list())
    p = out.vertex_matrix()
    fine = out.face_matrix()[level == 2]
    assert (p[fine, 2] > 0.5).all()
    assert r["faces_out"] < 4 * len(quads_in)


def test_error_threshold_refines_more_where_the_surface_bends_more():
    ms = load_polygons("quad/spot_quadrangulated.obj")
    nv = ms.current_mesh().vertex_number()
    ms.compute_curvature_principal_directions_per_vertex(method="Quadric Fitting", curvcolormethod="Mean Curvature")
    mean_curvature = np.abs(ms.current_mesh().vertex_scalar_array().copy())
    r = ms.meshing_surface_subdivision_interpolatory_quad(iterations=2, adaptive=2,
                                                         error_threshold=pymeshlab.PercentageValue(0.05))
    out = ms.current_mesh()
    assert face_levels_are_balanced(out) == 1
    assert ms.get_topological_measures()["boundary_edges"] == 0
    level = out.face_custom_scalar_attribute_array("subdivision_level")
    faces = out.face_matrix()
    # an input vertex is refined around when a face of level >= 1 touches it
    refined = np.zeros(nv, dtype=bool)
    touched = faces[level >= 1].ravel()
    refined[touched[touched < nv]] = True
    assert 0.05 < refined.mean() < 0.9 and r["levels"] == 2
    # measured: median |H| 3.3 around refined faces, 1.9 elsewhere
    assert np.median(mean_curvature[refined]) > 1.5 * np.median(mean_curvature[~refined])
    # a lower threshold refines more
    ms.set_current_mesh(0)
    finer = ms.meshing_surface_subdivision_interpolatory_quad(iterations=2, adaptive=2,
                                                             error_threshold=pymeshlab.PercentageValue(0.02))
    assert finer["faces_out"] > r["faces_out"] and finer["faces_refined_level_0"] > r["faces_refined_level_0"]


def test_adaptive_refinement_gives_the_same_mesh_twice():
    # Error-driven refinement picks faces by a threshold and balances their neighbours; the
    # same input and parameters must give the same polygons, level by level.
    runs = []
    for _ in range(2):
        ms = load_polygons("quad/spot_quadrangulated.obj")
        ms.meshing_surface_subdivision_interpolatory_quad(iterations=2, adaptive=2,
                                                          error_threshold=pymeshlab.PercentageValue(0.05))
        out = ms.current_mesh()
        runs.append((out.vertex_matrix().copy(), out.face_matrix().copy(), out.polygonal_face_list(),
                     out.face_custom_scalar_attribute_array("subdivision_level").copy()))
    (v0, f0, p0, l0), (v1, f1, p1, l1) = runs
    assert np.array_equal(v0, v1) and np.array_equal(f0, f1) and np.array_equal(l0, l1)
    assert [list(p) for p in p0] == [list(p) for p in p1]


@pytest.mark.parametrize("bad, message", [(dict(adaptive=1), "no face is selected"),
                                          (dict(adaptive=2, error_threshold=pymeshlab.PureValue(0)), "error_threshold")])
def test_bad_adaptive_input_raises_and_leaves_the_mesh(bad, message):
    ms = load_polygons("quad/torus_quad.off")
    before = snapshot(ms.current_mesh())
    with raises_on(ms, message):
        ms.meshing_surface_subdivision_interpolatory_quad(**bad)
    assert ms.mesh_number() == 1
    assert_unchanged(before, ms.current_mesh())


def cube_polygons():
    v = np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0], [0, 0, 1], [1, 0, 1], [1, 1, 1], [0, 1, 1]], dtype=float)
    faces = [[0, 3, 2, 1], [4, 5, 6, 7], [0, 1, 5, 4], [1, 2, 6, 5], [2, 3, 7, 6], [3, 0, 4, 7]]
    ms = pymeshlab.MeshSet()
    ms.add_mesh(pymeshlab.Mesh(vertex_matrix=v, face_list_of_indices=[np.array(f, dtype=np.uint32) for f in faces]))
    return ms


def total_angle_at(mesh, v):
    """Sum of the triangle angles at vertex v, in degrees: 360 where the surface is smooth."""
    p, total = mesh.vertex_matrix(), 0.0
    for f in mesh.face_matrix():
        if v in f:
            k = list(f).index(v)
            a, b = p[f[(k + 1) % 3]] - p[v], p[f[(k + 2) % 3]] - p[v]
            total += np.degrees(np.arccos(a @ b / np.linalg.norm(a) / np.linalg.norm(b)))
    return total


def test_a_selected_vertex_becomes_a_cusp():
    pointed, rounded = cube_polygons(), cube_polygons()
    pointed.compute_selection_by_condition_per_vertex(condselect="(x < 0.5) && (y < 0.5) && (z < 0.5)")
    r = pointed.meshing_surface_subdivision_interpolatory_quad(iterations=3, use_selected_vertices_as_cusps=True)
    rounded.meshing_surface_subdivision_interpolatory_quad(iterations=3)
    assert r["cusps"] == 1
    np.testing.assert_array_equal(pointed.current_mesh().vertex_matrix()[0], [0, 0, 0])
    # the cube corner at vertex 0 stays a cone (input: 3 x 90 degrees; measured 297 after 3 steps);
    # without the cusp it flattens towards a tangent plane (measured 340, the slow valence-3 limit)
    assert total_angle_at(pointed.current_mesh(), 0) < 310
    assert total_angle_at(rounded.current_mesh(), 0) > 330
    # the opposite corner is no cusp: its angles barely change (measured 0.02 degrees)
    assert abs(total_angle_at(pointed.current_mesh(), 6) - total_angle_at(rounded.current_mesh(), 6)) < 0.1
