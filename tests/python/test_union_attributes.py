"""The union carries the bodies' colours and qualities over (transfer_* parameters, the
names of MeshLab's own Boolean filters) and records each face's body ("body" attribute).

A vertex quality that is a linear function of position is reproduced exactly by
barycentric interpolation, so the transferred quality measures where each output vertex
was found on the input: exactly (to rounding) without the sliver step, within the step's
deviation bound times the function's gradient with it.
"""
import json
import subprocess
import sys

import numpy as np
import pymeshlab
import pytest

from conftest import assert_unchanged, shared_mesh, snapshot

LAYERS, COMPONENTS = 0, 1
GRADIENT = np.array([1.0, 2.0, -1.0])  # quality = x + 2y - z
DEFAULT_DEVIATION = 2e-3  # the filter's sliver_max_deviation


def linear_quality(v):
    return v @ GRADIENT


def coloured_bodies():
    """A red cube with quality x + 2y - z and a blue sphere poking out of it, the same quality."""
    ms = pymeshlab.MeshSet()
    ms.create_cube(size=1.0)
    ms.compute_color_by_function_per_face(r="255", g="0", b="0")
    ms.compute_color_by_function_per_vertex(x="255", y="0", z="0")
    ms.compute_scalar_by_function_per_vertex(q="x+2*y-z")
    ms.create_sphere(radius=0.5, subdiv=3)
    ms.compute_matrix_from_translation(axisx=0.5, axisy=0.3, axisz=0.2)
    ms.compute_color_by_function_per_face(r="0", g="0", b="255")
    ms.compute_color_by_function_per_vertex(x="0", y="0", z="255")
    ms.compute_scalar_by_function_per_vertex(q="x+2*y-z")
    return ms


def transfer_all(ms, **kw):
    return ms.generate_surface_intersection_union(transfer_face_color=True, transfer_face_quality=True,
                                                  transfer_vert_color=True, transfer_vert_quality=True, **kw)


def diagonal(m):
    v = m.vertex_matrix()
    return float(np.linalg.norm(v.max(0) - v.min(0)))


@pytest.mark.parametrize("sliver", [0.0, 10.0])
def test_vertex_quality_is_interpolated_where_each_vertex_lies_on_the_input(sliver):
    ms = coloured_bodies()
    before = [snapshot(ms.mesh(i)) for i in range(2)]
    transfer_all(ms, bodies=LAYERS, sliver_angle=sliver)
    m = ms.current_mesh()
    error = np.abs(m.vertex_scalar_array() - linear_quality(m.vertex_matrix())).max()
    # Rounding of the constructed points (exact arrangement), else the step's bound.
    tolerance = 1e-12 if sliver == 0 else np.linalg.norm(GRADIENT) * DEFAULT_DEVIATION * diagonal(m)
    assert error <= tolerance
    for i in range(2):
        assert_unchanged(before[i], ms.mesh(i))


def test_face_colours_and_bodies_follow_the_faces_of_each_body():
    ms = coloured_bodies()
    transfer_all(ms, bodies=LAYERS, sliver_angle=0.0)
    m = ms.current_mesh()
    body = m.face_custom_scalar_attribute_array("body")
    colour = m.face_color_matrix()
    red, blue = np.array([1, 0, 0, 1.0]), np.array([0, 0, 1, 1.0])
    assert set(np.unique(body)) == {0.0, 1.0}
    assert np.allclose(colour[body == 0], red) and np.allclose(colour[body == 1], blue)
    # The cube's faces lie on its sides (|coordinate| = 0.5), the sphere's inside its ball.
    v, f = m.vertex_matrix(), m.face_matrix()
    centroid = v[f].mean(1)
    assert np.all(np.abs(np.abs(centroid[body == 0]).max(1) - 0.5) < 1e-12)
    assert np.all(np.linalg.norm(centroid[body == 1] - [0.5, 0.3, 0.2], axis=1) <= 0.5 + 1e-12)
    # Vertex colours: pure red or blue at input vertices, a mix at the intersection points
    # (which lie on both bodies; each takes one).
    vc = m.vertex_color_matrix()
    assert np.all(np.isclose(vc, red).all(1) | np.isclose(vc, blue).all(1))


def test_without_transfer_the_union_has_no_colour_and_missing_attributes_are_grey():
    ms = coloured_bodies()
    ms.generate_surface_intersection_union(bodies=LAYERS)
    assert not ms.current_mesh().has_face_color()
    # A body without face colour gives MeshLab's grey, as its Boolean filters do.
    ms = pymeshlab.MeshSet()
    ms.create_cube(size=1.0)
    ms.create_sphere(radius=0.5, subdiv=2)
    ms.compute_matrix_from_translation(axisx=0.5)
    ms.compute_color_by_function_per_face(r="0", g="255", b="0")
    ms.generate_surface_intersection_union(bodies=LAYERS, transfer_face_color=True)
    m = ms.current_mesh()
    body, colour = m.face_custom_scalar_attribute_array("body"), m.face_color_matrix()
    assert np.allclose(colour[body == 0], [128 / 255, 128 / 255, 128 / 255, 1])
    assert np.allclose(colour[body == 1], [0, 1, 0, 1])


def test_box_plates_keep_their_own_faces_through_the_sliver_step():
    """box.STL's ten plates as layers, face quality = plate index. Where the sliver step
    removes a vertex of an intersection line, its star is refilled on both sides of the line:
    each new face must keep a source on its own side. Measured: every vertex of the union's
    faces tagged with plate k lies within the step's bound of plate k (0.0154 against 0.0187;
    before the sources took sides, a face's centroid was 1.2 away from its plate)."""
    ms = pymeshlab.MeshSet()
    ms.load_new_mesh(str(shared_mesh("multicomponent/box.STL")))
    ms.meshing_remove_duplicate_vertices()
    ms.generate_splitting_by_connected_components()
    plates = [(ms.mesh(i).vertex_matrix(), ms.mesh(i).face_matrix()) for i in range(1, ms.mesh_number())]
    assert len(plates) == 10
    ms = pymeshlab.MeshSet()
    for k, (v, f) in enumerate(plates):
        ms.add_mesh(pymeshlab.Mesh(v, f, f_scalar_array=np.full(len(f), float(k))))
    result = ms.generate_surface_intersection_union(bodies=LAYERS, transfer_face_quality=True)
    assert result["slivers_collapsed"] > 0
    union_id = ms.current_mesh_id()
    m = ms.current_mesh()
    quality = m.face_scalar_array()
    assert np.array_equal(quality, m.face_custom_scalar_attribute_array("body"))
    bound = DEFAULT_DEVIATION * diagonal(m)
    for k in range(10):
        ms.set_current_mesh(union_id)
        ms.compute_selection_by_condition_per_face(condselect=f"fq == {k}")
        ms.generate_from_selected_faces()
        part = ms.current_mesh_id()
        # Every vertex of plate k's faces (not face interiors: where the step straightened a
        # line between two plates, a face of one may reach over the other's side of the old
        # line, within the bound of the union's surface but not of its own plate).
        d = ms.get_hausdorff_distance(sampledmesh=part, targetmesh=k, samplevert=True, sampleface=False,
                                      samplenum=ms.current_mesh().vertex_number())
        assert d["max"] <= bound, f"plate {k}: {d['max']} > {bound}"


def test_components_mode_maps_faces_back_to_the_one_mesh():
    """rabbit.obj's nine blobs in one layer, face quality = face index: every union face of
    body b takes the quality of a face of component b, the one nearest its centroid."""
    ms = pymeshlab.MeshSet()
    ms.load_new_mesh(str(shared_mesh("multicomponent/rabbit.obj")))
    ms.meshing_poly_to_tri() if hasattr(ms, "meshing_poly_to_tri") else None
    src = ms.current_mesh()
    v, f = src.vertex_matrix(), src.face_matrix()
    ms = pymeshlab.MeshSet()
    ms.add_mesh(pymeshlab.Mesh(v, f, f_scalar_array=np.arange(len(f), dtype=float)))
    transfer_all(ms, bodies=COMPONENTS, sliver_angle=0.0)
    m = ms.current_mesh()
    index = m.face_scalar_array().astype(int)
    assert np.array_equal(index, m.face_scalar_array())
    # Each union face lies in the input face whose index it got (the exact arrangement).
    uv, uf = m.vertex_matrix(), m.face_matrix()
    tri = v[f[index]]
    n = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
    n /= np.linalg.norm(n, axis=1)[:, None]
    for z in range(3):
        assert np.abs(((uv[uf[:, z]] - tri[:, 0]) * n).sum(1)).max() < 1e-9
    assert len(np.unique(m.face_custom_scalar_attribute_array("body"))) == 9


def test_cli_union_transfers_attributes(tmp_path):
    out = tmp_path / "u.ply"
    ms = coloured_bodies()
    a, b = tmp_path / "a.ply", tmp_path / "b.ply"
    for i, path in ((0, a), (1, b)):
        ms.set_current_mesh(i)
        ms.save_current_mesh(str(path), save_vertex_color=True, save_face_color=True)
    proc = subprocess.run([sys.executable, "-m", "meshregrid", "union", str(a), str(b), str(out),
                           "--transfer-attributes"], capture_output=True, text=True, check=True)
    assert json.loads(proc.stdout)["bodies"] == 2
    ms = pymeshlab.MeshSet()
    ms.load_new_mesh(str(out))
    colour = ms.current_mesh().face_color_matrix()
    assert {tuple(c) for c in np.round(colour, 6)} == {(1, 0, 0, 1), (0, 0, 1, 1)}


def test_face_colours_map_back_through_deleted_faces_of_the_input():
    """A layer whose first faces were deleted (MeshLab keeps them as deleted elements until
    compacted): the colours still come from the right faces. Every face of the cube gets its
    own colour; each union face of the cube must carry the colour of the cube face it lies in."""
    cube = pymeshlab.MeshSet()
    cube.create_cube(size=1.0)
    cv, cf = cube.current_mesh().vertex_matrix(), cube.current_mesh().face_matrix()
    tv = np.array([[9, 9, 9], [10, 9, 9], [9, 10, 9], [9, 9, 10.0]])
    tf = np.array([[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]])
    v = np.vstack([tv, cv])
    f = np.vstack([tf, cf + len(tv)])
    colours = np.ones((len(f), 4))
    colours[len(tf):, 0] = np.arange(len(cf)) / len(cf)
    colours[len(tf):, 1] = 1 - np.arange(len(cf)) / len(cf)
    ms = pymeshlab.MeshSet()
    ms.add_mesh(pymeshlab.Mesh(v, f, f_color_matrix=colours))
    ms.compute_selection_by_condition_per_face(condselect="x0 > 5")
    ms.meshing_remove_selected_vertices_and_faces()
    assert ms.current_mesh().face_number() == len(cf)
    ms.create_sphere(radius=0.5, subdiv=2)
    ms.compute_matrix_from_translation(axisx=0.5, axisy=0.2)
    ms.generate_surface_intersection_union(bodies=LAYERS, transfer_face_color=True, sliver_angle=0.0)
    m = ms.current_mesh()
    body, got = m.face_custom_scalar_attribute_array("body"), m.face_color_matrix()
    uv, uf = m.vertex_matrix(), m.face_matrix()
    centroid = uv[uf].mean(1)
    tri = cv[cf]
    normal = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
    normal /= np.linalg.norm(normal, axis=1)[:, None]
    checked = 0
    for i in np.where(body == 0)[0]:
        # The cube face containing the centroid: in its plane and inside its three sides.
        for k in range(len(cf)):
            if abs((centroid[i] - tri[k, 0]) @ normal[k]) > 1e-12:
                continue
            inside = all(np.cross(tri[k, (z + 1) % 3] - tri[k, z], centroid[i] - tri[k, z]) @ normal[k] >= -1e-12
                         for z in range(3))
            if inside:
                assert np.allclose(got[i], colours[len(tf) + k], atol=1 / 255), f"face {i}"
                checked += 1
                break
    assert checked == int((body == 0).sum()) > 0
