"""Regression tests of meshing_surface_subdivision_interpolatory_quad through PyMeshLab."""
import collections

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


@pytest.mark.parametrize("name", QUAD_MESHES)
def test_every_input_vertex_is_kept_bit_for_bit_and_the_output_is_quads(name):
    ms = load_polygons(name)
    before = snapshot(ms.current_mesh())
    polygons = polygon_sizes(ms.current_mesh())
    r = ms.meshing_surface_subdivision_interpolatory_quad(iterations=1)
    assert_unchanged(before, ms.mesh(0))  # the input layer is untouched
    out = ms.current_mesh()
    assert ms.mesh_number() == 2
    v_in = before[0]
    np.testing.assert_array_equal(out.vertex_matrix()[:len(v_in)], v_in)
    quads_in = sum(c if n == 4 else n * c for n, c in polygons.items())  # non-quads split into n quads
    assert r["faces_out"] == 4 * quads_in
    assert polygon_sizes(out) == {4: r["faces_out"]}
    assert np.isfinite(out.vertex_matrix()).all()


@pytest.mark.parametrize("name", ["quad/quadknot.obj", "quad/torus_quad.off"])
def test_closed_genus_one_nets_stay_closed_with_the_same_genus(name):
    ms = load_polygons(name)
    ms.meshing_surface_subdivision_interpolatory_quad(iterations=2)
    topo = ms.get_topological_measures()
    assert topo["boundary_edges"] == 0
    assert topo["is_mesh_two_manifold"]
    assert topo["genus"] == 1


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
