#!/usr/bin/env python3
"""Damaged inputs for the advancing-front remesher: it must return (or refuse with a
PyMeshLabException) within a time limit, never crash or hang.

Usage: .venv/bin/python scripts/fuzz_remesh.py FIRST_SEED LAST_SEED [--timeout S]
Seeds run from FIRST_SEED up to LAST_SEED, which is left out (as in range()).
Seed s damages one shared mesh (s % 4: fandisk, part, bunny, blade) in one way (s % 7):
drop 20% of the faces, noise of 1% of the diagonal on every vertex, reversed copies of 10% of
the faces, every 30th vertex moved onto the next (zero-area faces), keep 5% of the faces,
flatten one axis, a shifted copy added; target length, ridge angle and relax_wedges are drawn
from the seed.
Each case runs in its own process, so a crash or a hang is seen as such. Prints one line per
seed and the failing seeds at the end; not part of the test suite.
"""
import pathlib
import sys

from fuzz_cases import run_seeds, seed_range

REPO = pathlib.Path(__file__).resolve().parents[1]
DATA = REPO.parent / "shared" / "data"
MESHES = ["cad/fandisk.obj", "cad/part.off", "organic/stanford-bunny.obj", "cad/blade.off"]
DAMAGES = ["drop 20% of the faces", "1% noise", "reversed copies of 10% of the faces",
           "every 30th vertex onto the next", "keep 5% of the faces", "flattened axis", "shifted copy added"]

CASE = r'''
import sys
import numpy as np
import meshregrid  # noqa: F401
import pymeshlab
seed, path = int(sys.argv[1]), sys.argv[2]
rng = np.random.default_rng(seed)
ms = pymeshlab.MeshSet()
ms.load_new_mesh(path)
v = ms.current_mesh().vertex_matrix().copy()
f = ms.current_mesh().face_matrix().copy()
diag = ms.current_mesh().bounding_box().diagonal()
kind = seed % 7
if kind == 0:
    f = f[rng.random(len(f)) > 0.2]
elif kind == 1:
    v = v + rng.normal(0, 0.01 * diag, v.shape)
elif kind == 2:
    pick = f[rng.random(len(f)) < 0.1]
    f = np.concatenate([f, pick[:, ::-1]])
elif kind == 3:
    for i in range(0, len(v) - 1, 30):
        v[i] = v[i + 1]
elif kind == 4:
    f = f[rng.random(len(f)) < 0.05]
elif kind == 5:
    v[:, int(rng.integers(0, 3))] = 0
else:
    f = np.concatenate([f, f + len(v)])
    v = np.concatenate([v, v + 0.1 * diag * rng.random(3)])
percent = float(rng.choice([0.5, 1, 2, 5]))
ridge = float(rng.choice([20, 30, 60]))
relax = bool(rng.integers(0, 2))
out = pymeshlab.MeshSet()
out.add_mesh(pymeshlab.Mesh(v, f))
try:
    r = out.meshing_advancing_front_remesh(target_length=pymeshlab.PureValue(percent / 100 * diag), ridge_angle=ridge,
                                           relax_wedges=relax)
    print(f"{percent}% ridge {ridge} relax {relax}: {out.current_mesh().face_number()} faces, "
          f"open sides {r['unmeshed_sides']}, unmeshed patches {r['unmeshed_patches']}")
except pymeshlab.PyMeshLabException as e:
    print(f"{percent}% ridge {ridge} relax {relax}: refused: {str(e).splitlines()[-1][:160]}")
'''


def main():
    seeds, timeout = seed_range(__doc__, 300)
    return run_seeds(CASE, seeds, lambda seed: (seed, DATA / MESHES[seed % 4]), lambda seed: f"{MESHES[seed % 4]}, {DAMAGES[seed % 7]}", timeout)


if __name__ == "__main__":
    sys.exit(main())
