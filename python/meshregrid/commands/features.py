"""``meshregrid features IN OUT``: feature lines and patches of a surface."""
import json
import pathlib

NAME = "features"
HELP = "detect ridges, corners, discrete lines and patches; write the mesh coloured by patch"


def add_arguments(p):
    p.add_argument("input", help="input surface (PLY, OBJ, OFF, STL, ...)")
    p.add_argument("output", help="output mesh, faces coloured by patch (PLY keeps colours)")
    p.add_argument("--ridge-angle", type=float, default=30.0, help="ridge angle in degrees (default 30)")
    p.add_argument("--corner-angle", type=float, default=45.0, help="corner angle in degrees (default 45)")
    p.add_argument("--min-patch-faces", type=int, default=0, help="merge smaller patches (default 0 = off)")
    p.add_argument("--lines", help="also write the discrete lines as a polyline mesh to this file")


def run(args) -> int:
    import pymeshlab
    from .. import pipelines

    ms = pymeshlab.MeshSet()
    ms.load_new_mesh(args.input)
    pipelines.weld_if_soup(ms, args.input)
    result = pipelines.detect_features(ms, args.ridge_angle, args.corner_angle, args.min_patch_faces,
                                       lines_layer=bool(args.lines))
    ms.save_current_mesh(args.output, save_face_color=True)
    if args.lines:
        ms.set_current_mesh(ms.mesh_number() - 1)
        ms.save_current_mesh(args.lines)
    print(json.dumps(result, indent=2, sort_keys=True))
    return 0
