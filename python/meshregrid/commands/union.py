"""``meshregrid union IN... OUT``: outer surface of the union of intersecting closed bodies."""
import json

NAME = "union"
HELP = "unite intersecting closed bodies (one per input file, or the components of one file)"


def add_arguments(p):
    p.add_argument("inputs", nargs="+", metavar="IN", help="input bodies (PLY, OBJ, OFF, STL, ...)")
    p.add_argument("output", metavar="OUT", help="output mesh")
    p.add_argument("--components", action="store_true",
                   help="every connected component of each input is a body (default: every file is one body)")
    p.add_argument("--sliver-angle", type=float, default=10.0,
                   help="collapse cut faces with an angle below this, degrees (default 10, 0 = off)")
    p.add_argument("--sliver-max-deviation", type=float, default=None,
                   help="how far the sliver step may move the surface, all moves together, fraction of the "
                        "diagonal (default: the filter's, 2e-3)")
    p.add_argument("--transfer-attributes", action="store_true",
                   help="carry the inputs' face and vertex colours and qualities over to the union")
    p.add_argument("--lines", help="also write the intersection lines to this OBJ file (v and l records)")
    p.add_argument("--remesh", action="store_true",
                   help="regrid the union with the advancing front, intersection lines kept as ridges")
    size = p.add_mutually_exclusive_group()
    size.add_argument("--target-length", type=float, help="remesh: absolute element size")
    size.add_argument("--target-percent", type=float, default=1.0,
                      help="remesh: element size in percent of the bounding-box diagonal (default 1)")
    p.add_argument("--ridge-angle", type=float, default=30.0, help="remesh: ridge angle in degrees (default 30)")
    p.add_argument("--relax-wedges", action="store_true",
                   help="remesh: lines leaving a point at under 30 degrees may share their first segment, "
                        "and lines passing closer than 0.25 x the size meet there")


def write_polylines(mesh, path) -> None:
    """Edges of an edge mesh as OBJ line records (MeshLab's exporters drop edges)."""
    with open(path, "w") as f:
        f.write("# intersection lines of a MeshRegrid union\n")
        for x, y, z in mesh.vertex_matrix():
            f.write(f"v {x:.17g} {y:.17g} {z:.17g}\n")
        for a, b in mesh.edge_matrix():
            f.write(f"l {a + 1} {b + 1}\n")


def run(args) -> int:
    import pymeshlab
    from .. import pipeline_union, pipelines

    ms = pymeshlab.MeshSet()
    for path in args.inputs:
        ms.load_new_mesh(path)
        pipelines.weld_if_soup(ms, path)
    if args.components and len(args.inputs) > 1:
        ms.generate_by_merging_visible_meshes()
        merged = ms.current_mesh_id()
        for i in range(merged):
            ms.set_mesh_visibility(i, False)
        ms.set_current_mesh(merged)
    result = pipeline_union.union(
        ms, bodies="components" if args.components else "layers", sliver_angle=args.sliver_angle,
        sliver_max_deviation=args.sliver_max_deviation, lines_layer=bool(args.lines), remesh=args.remesh,
        target_length=args.target_length, target_percent=args.target_percent, ridge_angle=args.ridge_angle,
        transfer_attributes=args.transfer_attributes, relax_wedges=args.relax_wedges)
    union_id = result["union_layer"]
    if args.lines:
        write_polylines(ms.mesh(union_id + 1), args.lines)
    ms.set_current_mesh(result["remesh_layer"] if args.remesh else union_id)
    ms.save_current_mesh(args.output)
    print(json.dumps(result, indent=2, sort_keys=True))
    if args.remesh and result["remesh"].get("unmeshed_sides", 0) != 0:
        return 3
    return 0
