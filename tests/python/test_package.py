"""The meshregrid package: plugin loading errors and the command-line entry point."""
import os
import subprocess
import sys

import pymeshlab

import meshregrid


def run_python(code, **env):
    return subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120,
                          env={**os.environ, **env})


def test_filters_are_bound_as_meshset_methods():
    assert hasattr(pymeshlab.MeshSet, "compute_feature_lines_and_patches")
    assert "compute_feature_lines_and_patches" in meshregrid.available_filters()


def test_missing_plugins_give_an_error_that_names_the_build_command(tmp_path):
    r = run_python("import meshregrid", MESHREGRID_PLUGIN_DIR=str(tmp_path))
    assert r.returncode != 0
    assert "scripts/setup" in r.stderr and str(tmp_path) in r.stderr


def test_cli_help_lists_subcommands():
    r = subprocess.run([sys.executable, "-m", "meshregrid", "--help"], capture_output=True, text=True, timeout=120)
    assert r.returncode == 0
    assert "features" in r.stdout and "demo" in r.stdout


def test_cli_reports_bad_input_without_a_traceback(tmp_path):
    bad = tmp_path / "points.ply"
    ms = pymeshlab.MeshSet()
    ms.create_sphere()
    ms.set_selection_all()
    ms.meshing_remove_selected_faces()
    ms.save_current_mesh(str(bad))
    r = subprocess.run([sys.executable, "-m", "meshregrid", "features", str(bad), str(tmp_path / "o.ply")],
                       capture_output=True, text=True, timeout=120)
    assert r.returncode == 1
    assert "no faces" in r.stderr and "Traceback" not in r.stderr


def test_hausdorff_measures_far_layers_too():
    # PyMeshLab drops samples beyond maxdist (default half a diagonal) from the maximum: a
    # layer moved far away must still measure its full distance. Unit cubes, one shifted by 3
    # along x: a point (x, y, z) of the first is 3 - x from the second, at most 3 (x = 0).
    from meshregrid.quality import hausdorff, one_way_hausdorff
    ms = pymeshlab.MeshSet()
    ms.add_mesh(pymeshlab.Mesh(*_unit_cube(0.0)))
    ms.add_mesh(pymeshlab.Mesh(*_unit_cube(3.0)))
    assert abs(one_way_hausdorff(ms, 0, 1, 5000) - 3.0) < 1e-9
    assert abs(hausdorff(ms, 0, 1, 5000) - 3.0) < 1e-9
    assert ms.current_mesh_id() == 1  # (the last added stays current)


def _unit_cube(x0):
    import numpy as np
    v = np.array([[x, y, z] for x in (0, 1) for y in (0, 1) for z in (0, 1)], float)
    v[:, 0] += x0
    f = np.array([[0, 1, 3], [0, 3, 2], [4, 6, 7], [4, 7, 5], [0, 4, 5], [0, 5, 1],
                  [2, 3, 7], [2, 7, 6], [0, 2, 6], [0, 6, 4], [1, 5, 7], [1, 7, 3]])
    return v, f
