"""``meshregrid subdivide IN OUT``: interpolatory quad subdivision."""
import json

NAME = "subdivide"
HELP = "refine a quad (or polygon) mesh by interpolatory quad subdivision; write OUT (OBJ keeps quads)"


def add_arguments(p):
    p.add_argument("input", help="input polygon mesh (OBJ keeps quads; OFF, PLY, ...)")
    p.add_argument("output", help="output mesh; use .obj to keep the quads")
    p.add_argument("--iterations", type=int, default=1, help="subdivision steps (default 1)")
    p.add_argument("--w", type=float, default=1.0, help="tension in [0, 1.236] (default 1: cubic precision)")
    p.add_argument("--crease-angle", type=float, default=0.0, help="keep edges sharper than this sharp (0 = off)")


def run(args) -> int:
    import pymeshlab

    ms = pymeshlab.MeshSet()
    ms.load_new_mesh(args.input)
    result = ms.meshing_surface_subdivision_interpolatory_quad(
        iterations=args.iterations, w=args.w, crease_angle=args.crease_angle)
    ms.save_current_mesh(args.output)
    print(json.dumps(result, indent=2, sort_keys=True))
    return 0
