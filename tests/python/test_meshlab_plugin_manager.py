"""MeshLab's own PluginManager (what the desktop application runs at start-up) loads our
plugins, and every filter sits in the menu class users expect.

MeshLab's built-in plugins are not loaded here: they register keyboard shortcuts, which needs
a GUI application and a platform plugin the PyMeshLab wheel does not ship."""
import pathlib
import subprocess

import pytest

import meshregrid

LISTER = pathlib.Path(meshregrid.plugin_dir()).parent / "tests" / "gui" / "list_meshlab_filters"

# FilterPlugin::FilterClass bits from MeshLab 2025.07's filter_plugin.h
SELECTION, CLEANING, REMESHING, MESH_CREATION = 0x1, 0x2, 0x4, 0x40
EXPECTED_CLASS = {
    "compute_feature_lines_and_patches": SELECTION,
    "meshing_advancing_front_remesh": REMESHING,
    "meshing_surface_subdivision_interpolatory_quad": REMESHING,
    "meshing_heal_patch_gaps": CLEANING,
    "generate_surface_intersection_union": MESH_CREATION,
}


@pytest.fixture(scope="module")
def listed():
    if not LISTER.is_file():
        pytest.fail(f"{LISTER} not built: run scripts/setup")
    out = subprocess.run([str(LISTER), str(meshregrid.plugin_dir())],
                         capture_output=True, text=True, timeout=120, check=True).stdout
    rows = {}
    for line in out.splitlines():
        plugin, python_name, menu_name, klass, nparams = line.split("\t")
        rows[python_name] = (plugin, menu_name, int(klass), int(nparams))
    return rows


def test_meshlab_loads_every_filter_pymeshlab_loads(listed):
    ours = meshregrid.available_filters()
    assert "compute_feature_lines_and_patches" in ours
    for name in ours:
        assert name in listed, f"{name} loads in PyMeshLab but not through MeshLab's PluginManager"


def test_each_filter_is_in_the_expected_menu_with_parameters_and_a_marked_name(listed):
    for name in meshregrid.available_filters():
        plugin, menu_name, klass, nparams = listed[name]
        assert klass & EXPECTED_CLASS[name], f"{name}: class bits {klass:#x}"
        assert nparams > 0
        assert "MeshRegrid" in menu_name and plugin.startswith("MeshRegrid")
