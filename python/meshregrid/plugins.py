"""Finding, loading and binding the MeshRegrid MeshLab plugins."""
import os
import pathlib

import pymeshlab

# Each plugin of the project and the PyMeshLab filter names it adds.
FILTERS = {
    "filter_meshregrid_features": ["compute_feature_lines_and_patches"],
    "filter_meshregrid_remesh": ["meshing_advancing_front_remesh"],
    "filter_meshregrid_union": ["generate_surface_intersection_union"],
    "filter_meshregrid_healing": ["meshing_heal_patch_gaps"],
    "filter_meshregrid_quadsub": ["meshing_surface_subdivision_interpolatory_quad"],
}
# Without these the package is of no use: their absence is an error at import.
REQUIRED = ["filter_meshregrid_features"]

_BUILD_HINT = "build them with scripts/setup (or set MESHREGRID_PLUGIN_DIR to the folder holding the .so files)"
_loaded = False


def plugin_dir() -> pathlib.Path:
    """The folder holding the built plugins: $MESHREGRID_PLUGIN_DIR or <repo>/build/plugins."""
    env = os.environ.get("MESHREGRID_PLUGIN_DIR")
    if env:
        return pathlib.Path(env)
    return pathlib.Path(__file__).resolve().parents[2] / "build" / "plugins"


def available_filters():
    """PyMeshLab names of the MeshRegrid filters that are loaded."""
    return [f for names in FILTERS.values() for f in names if hasattr(pymeshlab.MeshSet, f)]


def load_plugins() -> None:
    """Loads every built MeshRegrid plugin once and binds the new filters on MeshSet."""
    global _loaded
    if _loaded:
        return
    folder = plugin_dir()
    missing = [name for name in REQUIRED if not (folder / f"lib{name}.so").is_file()]
    if missing:
        raise ImportError(f"MeshRegrid plugins not found in {folder}: {', '.join(missing)}; {_BUILD_HINT}")
    known = set(pymeshlab.filter_list())
    for name, filters in FILTERS.items():
        path = folder / f"lib{name}.so"
        if path.is_file() and not set(filters) <= known:
            pymeshlab.load_plugin(str(path))
    # Bind the way pymeshlab/__init__.py does for its own filters.
    for filter_name in pymeshlab.filter_list():
        if not hasattr(pymeshlab.MeshSet, filter_name):
            setattr(pymeshlab.MeshSet, filter_name, pymeshlab.bind_function(filter_name))
    absent = [f for name, filters in FILTERS.items() if (folder / f"lib{name}.so").is_file()
              for f in filters if not hasattr(pymeshlab.MeshSet, f)]
    if absent:
        raise ImportError(f"MeshRegrid plugins loaded but these filters are missing: {absent}; {_BUILD_HINT}")
    _loaded = True
