"""Pipelines chaining MeshRegrid filters on a pymeshlab.MeshSet."""
import pymeshlab


def detect_features(ms: pymeshlab.MeshSet, ridge_angle: float = 30.0, corner_angle: float = 45.0,
                    min_patch_faces: int = 0, lines_layer: bool = True, min_line_length: float = 0.0) -> dict:
    """Runs compute_feature_lines_and_patches on the current mesh and returns its dictionary.

    With ``lines_layer`` the discrete lines are added as a new edge-mesh layer and the
    current mesh stays the input mesh. ``min_line_length`` (absolute, 0 = keep every ridge)
    drops short ridge lines with an open end and short closed ridge loops.
    """
    current = ms.current_mesh_id()
    result = ms.compute_feature_lines_and_patches(
        ridge_angle=ridge_angle, corner_angle=corner_angle, min_patch_faces=min_patch_faces,
        create_lines_layer=lines_layer, min_line_length=pymeshlab.PureValue(min_line_length))
    ms.set_current_mesh(current)
    return result


def weld_if_soup(ms: pymeshlab.MeshSet, path: str) -> None:
    """STL files are triangle soups: weld coincident vertices so edges are shared."""
    if str(path).lower().endswith(".stl"):
        ms.meshing_remove_duplicate_vertices()
