# The installed Python package (PYTHONPATH=PREFIX/lib/python3.X/dist-packages)
# imports from PREFIX and parameterizes a small disk. Argument: PREFIX.
import os
import sys

import numpy as np

import intrinsic

prefix = os.path.realpath(sys.argv[1])
assert os.path.realpath(intrinsic.__file__).startswith(prefix), intrinsic.__file__
V = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [-1, 0, 0], [0, -1, 0]], dtype=np.float64)
F = np.array([[0, 1, 2], [0, 2, 3], [0, 3, 4], [0, 4, 1]], dtype=np.int32)
r = intrinsic.parameterize(V, F)
assert r.uv.shape == (5, 2) and r.flipped_triangles == 0
print("python package ok:", intrinsic.__file__)
