"""Finding, loading and binding the MeshRegrid MeshLab plugins."""
import os
import pathlib

import pymeshlab

# The filters each plugin adds, as PyMeshLab names (kept in step with plugins/).
FILTERS = {
    "filter_meshregrid_features": ["compute_feature_lines_and_patches"],
}

_BUILD_HINT = "build them with scripts/setup (or set MESHREGRID_PLUGIN_DIR to the folder holding the .so files)"
_loaded = False


def plugin_dir() -> pathlib.Path:
    """The folder holding the built plugins: $MESHREGRID_PLUGIN_DIR or <repo>/build/plugins."""
    env = os.environ.get("MESHREGRID_PLUGIN_DIR")
    if env:
        return pathlib.Path(env)
    return pathlib.Path(__file__).resolve().parents[2] / "build" / "plugins"


def load_plugins() -> None:
    """Loads every MeshRegrid plugin once and binds the new filters on MeshSet."""
    global _loaded
    if _loaded:
        return
    folder = plugin_dir()
    missing = [name for name in FILTERS if not (folder / f"lib{name}.so").is_file()]
    if missing:
        raise ImportError(f"MeshRegrid plugins not found in {folder}: {', '.join(missing)}; {_BUILD_HINT}")
    known = set(pymeshlab.filter_list())
    for name in FILTERS:
        if not set(FILTERS[name]) <= known:
            pymeshlab.load_plugin(str(folder / f"lib{name}.so"))
    # Bind the way pymeshlab/__init__.py does for its own filters.
    for filter_name in pymeshlab.filter_list():
        if not hasattr(pymeshlab.MeshSet, filter_name):
            setattr(pymeshlab.MeshSet, filter_name, pymeshlab.bind_function(filter_name))
    absent = [f for names in FILTERS.values() for f in names if not hasattr(pymeshlab.MeshSet, f)]
    if absent:
        raise ImportError(f"MeshRegrid plugins loaded but these filters are missing: {absent}; {_BUILD_HINT}")
    _loaded = True
