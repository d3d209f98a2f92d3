"""Pipeline: feature lines and patches, then advancing-front remeshing, with sane defaults."""
import pymeshlab

from . import pipelines

RECOVERY = {"linear": 0, "closest": 1, "quadratic": 2, "cubic": 3}


def remesh(ms: pymeshlab.MeshSet, target_length=None, target_percent: float = 1.0, ridge_angle: float = 30.0,
           corner_angle: float = 45.0, max_surface_error: float = 0.0, gradation: float = 1.3,
           recovery: str = "linear", improvement_iterations: int = 3, min_line_length=None,
           progress: bool = False, relax_wedges: bool = False) -> dict:
    """Remeshes the current mesh of ``ms`` into a new layer (which becomes current).

    ``target_length`` is absolute; without it ``target_percent`` of the bounding-box diagonal
    is used (1% by default). ``min_line_length`` (absolute; default: twice the target length, 0 keeps
    every ridge and corner) drops short ridge lines with an open end and short closed ridge
    loops in both steps, so they agree on the features. ``max_surface_error`` (absolute,
    0 = off) turns on curvature adaptation. ``relax_wedges`` lets two lines that leave a point at
    under 30 degrees share their first segment, and lines that pass closer than a quarter of the
    size meet there (the filter's parameter). Returns the filter's dictionary plus ``features``, the feature filter's
    dictionary on the input (the input keeps its geometry; the feature filter only adds
    selections, colours and the ``patch_id`` attribute).
    """
    if recovery not in RECOVERY:
        raise ValueError(f"recovery must be one of {sorted(RECOVERY)}, got {recovery!r}")
    source = ms.current_mesh_id()
    absolute = (target_length if target_length is not None
                else target_percent / 100.0 * ms.current_mesh().bounding_box().diagonal())
    min_line = 2 * absolute if min_line_length is None else min_line_length
    features = pipelines.detect_features(ms, ridge_angle=ridge_angle, corner_angle=corner_angle, lines_layer=False,
                                         min_line_length=min_line)
    ms.set_current_mesh(source)
    length = (pymeshlab.PureValue(target_length) if target_length is not None
              else pymeshlab.PercentageValue(target_percent))
    if progress:
        ms.set_verbosity(True)
    try:
        result = ms.meshing_advancing_front_remesh(
            target_length=length, ridge_angle=ridge_angle, corner_angle=corner_angle,
            max_surface_error=pymeshlab.PureValue(max_surface_error), gradation=gradation,
            recovery=RECOVERY[recovery], improvement_iterations=improvement_iterations,
            min_line_length=pymeshlab.PureValue(min_line), relax_wedges=relax_wedges)
    finally:
        if progress:
            ms.set_verbosity(False)
    result["features"] = features
    return result
