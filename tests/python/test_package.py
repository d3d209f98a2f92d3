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
