"""``meshregrid heal IN... OUT``: close gaps, overlaps and T-junctions between patches."""
import json

NAME = "heal"
HELP = "heal gaps, overlaps and T-junctions between surface patches (one file: its components; several: one patch each)"


def add_arguments(p):
    p.add_argument("inputs", nargs="+", metavar="IN", help="patch file(s) (PLY, OBJ, OFF, STL, ...)")
    p.add_argument("output", help="output mesh")
    tol = p.add_mutually_exclusive_group()
    tol.add_argument("--tolerance", type=float, help="vertex tolerance, absolute")
    tol.add_argument("--tolerance-percent", type=float, default=0.1,
                     help="vertex tolerance in percent of the bounding-box diagonal (default 0.1)")
    p.add_argument("--edge-tolerance", type=float, default=0.0,
                   help="edge verification tolerance, absolute (default 0 = the vertex tolerance)")
    p.add_argument("--feature-angle", type=float, default=30.0, help="feature angle in degrees (default 30)")


def run(args) -> int:
    import pymeshlab
    from .. import pipelines

    ms = pymeshlab.MeshSet()
    for path in args.inputs:
        ms.load_new_mesh(path)
        pipelines.weld_if_soup(ms, path)
    tol = (pymeshlab.PureValue(args.tolerance) if args.tolerance is not None
           else pymeshlab.PercentageValue(args.tolerance_percent))
    result = ms.meshing_heal_patch_gaps(
        patch_source=2 if len(args.inputs) > 1 else 0, vertex_tolerance=tol,
        edge_tolerance=pymeshlab.PureValue(args.edge_tolerance), feature_angle=args.feature_angle)
    ms.save_current_mesh(args.output)
    print(json.dumps(result, indent=2, sort_keys=True))
    return 0
