"""MeshRegrid: MeshLab filter plugins for regridding surface triangulations.

Importing this package loads every MeshRegrid plugin into PyMeshLab and binds
its filters as ``pymeshlab.MeshSet`` methods, e.g.
``ms.compute_feature_lines_and_patches(ridge_angle=30)``.
"""
from .plugins import FILTERS, available_filters, load_plugins, plugin_dir  # noqa: F401

load_plugins()

from .pipelines import detect_features  # noqa: E402,F401
