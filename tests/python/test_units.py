"""The filters do not depend on the model's unit: scaled by a power of two (which rounds
nothing), every filter gives its output scaled by the same power, bit for bit. A length
tolerance written in absolute terms (1e-12, say) breaks this: the remesher's did, and gave
fandisk in other units 32 faces more (found by scaling the shared meshes by 2^-30 and 2^30)."""
import numpy as np
import pytest

import pymeshlab
from conftest import load

CASES = {
    "features": ("cad/fandisk.obj", "compute_feature_lines_and_patches", {}),
    "remesh": ("cad/fandisk.obj", "meshing_advancing_front_remesh",
               {"target_length": pymeshlab.PercentageValue(2.0)}),
    "remesh part": ("cad/part.off", "meshing_advancing_front_remesh", {}),
    "union": ("multicomponent/rabbit.obj", "generate_surface_intersection_union", {"bodies": 1}),
    "healing": ("healing/boeing.off", "meshing_heal_patch_gaps", {}),
    "quad subdivision": ("quad/spot_control_mesh.obj", "meshing_surface_subdivision_interpolatory_quad",
                         {"iterations": 2}),
}


def run(relative, filter_name, params, scale):
    src = load(relative)
    if relative.endswith("rabbit.obj"):
        src.meshing_poly_to_tri()
    m = src.current_mesh()
    ms = pymeshlab.MeshSet()
    ms.add_mesh(pymeshlab.Mesh(m.vertex_matrix() * scale, m.face_matrix()))
    if relative.startswith("quad/"):
        ms = src  # keeps the polygons (faux edges)
        ms.compute_matrix_from_scaling_or_normalization(axisx=scale, axisy=scale, axisz=scale)
    result = getattr(ms, filter_name)(**params)
    out = ms.current_mesh()
    return result, out.vertex_matrix() / scale, out.face_matrix(), out.face_selection_array()


@pytest.mark.parametrize("case", list(CASES))
def test_a_power_of_two_scale_gives_the_same_output_scaled(case):
    relative, filter_name, params = CASES[case]
    reference = run(relative, filter_name, params, 1.0)
    for k in (-30, 30):
        scaled = run(relative, filter_name, params, 2.0 ** k)
        np.testing.assert_array_equal(scaled[1], reference[1], err_msg=f"{case} at 2^{k}")
        np.testing.assert_array_equal(scaled[2], reference[2], err_msg=f"{case} at 2^{k}")
        np.testing.assert_array_equal(scaled[3], reference[3], err_msg=f"{case} at 2^{k}")
        for key, value in reference[0].items():
            if "time" in key or not isinstance(value, (int, float)):
                continue
            unit = 2.0 ** k if key in ("hausdorff", "largest_gap", "largest_move", "target_length") else 1.0
            assert scaled[0][key] == pytest.approx(value * unit, rel=1e-12), f"{case} {key} at 2^{k}"
