"""``meshregrid remesh IN OUT --target-length L``: advancing-front regridding of a surface."""
import json
import sys

NAME = "remesh"
HELP = "regrid a surface triangulation with the advancing front (features kept exactly)"


def add_arguments(p):
    p.add_argument("input", help="input surface (PLY, OBJ, OFF, STL, ...)")
    p.add_argument("output", help="output mesh")
    size = p.add_mutually_exclusive_group()
    size.add_argument("--target-length", type=float, help="absolute element size")
    size.add_argument("--target-percent", type=float, default=1.0,
                      help="element size in percent of the bounding-box diagonal (default 1)")
    p.add_argument("--ridge-angle", type=float, default=30.0, help="ridge angle in degrees (default 30)")
    p.add_argument("--corner-angle", type=float, default=45.0, help="corner angle in degrees (default 45)")
    p.add_argument("--min-line-length", type=float, default=None,
                   help="ridge lines with an open end and closed ridge loops shorter than this (absolute) are "
                        "not kept as features (default: twice the target length; 0 keeps every ridge)")
    p.add_argument("--max-surface-error", type=float, default=0.0,
                   help="chord-error bound for curvature adaptation, absolute (default 0 = uniform size)")
    p.add_argument("--gradation", type=float, default=1.3, help="size gradation >= 1 (default 1.3)")
    p.add_argument("--recovery", choices=["linear", "closest", "quadratic", "cubic"], default="linear",
                   help="surface recovery of the new points (default linear)")
    p.add_argument("--relax-wedges", action="store_true",
                   help="lines leaving a point at under 30 degrees may share their first segment, "
                        "and lines passing closer than 0.25 x the size meet there")
    p.add_argument("--no-progress", action="store_true", help="do not print the filter's progress")


def run(args) -> int:
    import pymeshlab
    from .. import pipeline_remesh, pipelines

    ms = pymeshlab.MeshSet()
    ms.load_new_mesh(args.input)
    pipelines.weld_if_soup(ms, args.input)
    result = pipeline_remesh.remesh(
        ms, target_length=args.target_length, target_percent=args.target_percent, ridge_angle=args.ridge_angle,
        corner_angle=args.corner_angle, max_surface_error=args.max_surface_error, gradation=args.gradation,
        recovery=args.recovery, min_line_length=args.min_line_length, progress=not args.no_progress and sys.stdout.isatty(),
        relax_wedges=args.relax_wedges)
    ms.save_current_mesh(args.output)
    print(json.dumps(result, indent=2, sort_keys=True))
    return 0 if result["unmeshed_sides"] == 0 else 3
