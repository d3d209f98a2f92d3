"""Shared fixtures: the shared test meshes and MeshSet helpers."""
import pathlib

import numpy as np
import pytest

import meshregrid  # noqa: F401  (loads the plugins)
import pymeshlab

REPO = pathlib.Path(__file__).resolve().parents[2]
SHARED_DATA = REPO.parent / "shared" / "data"


def shared_mesh(relative: str) -> pathlib.Path:
    path = SHARED_DATA / relative
    if not path.is_file():
        pytest.skip(f"shared mesh {relative} not found beside the repository")
    return path


def load(relative: str) -> pymeshlab.MeshSet:
    ms = pymeshlab.MeshSet()
    ms.load_new_mesh(str(shared_mesh(relative)))
    if relative.lower().endswith(".stl"):
        ms.meshing_remove_duplicate_vertices()
    return ms


def snapshot(mesh: pymeshlab.Mesh):
    """What must not change when a filter fails on a mesh."""
    return (mesh.vertex_matrix().copy(), mesh.face_matrix().copy(), mesh.vertex_number(), mesh.face_number())


def assert_unchanged(before, mesh: pymeshlab.Mesh):
    after = snapshot(mesh)
    assert before[2:] == after[2:]
    np.testing.assert_array_equal(before[0], after[0])
    np.testing.assert_array_equal(before[1], after[1])


# PyMeshLab 2025.07 keeps a pointer to the log of a MeshSet whose filter raised,
# and a later mesh load in another MeshSet writes to it (a use-after-free seen
# under valgrind). MeshSets whose filter failed are therefore kept alive for the
# whole session.
_FAILED_MESHSETS = []


def raises_on(ms: pymeshlab.MeshSet, match: str):
    """pytest.raises(PyMeshLabException, match=...) that also keeps `ms` alive."""
    _FAILED_MESHSETS.append(ms)
    return pytest.raises(pymeshlab.PyMeshLabException, match=match)
