"""The installed Python package, imported from its install folder (argv[1]), registers a scan pair."""
import pathlib
import sys

import numpy as np

import contour_reg as cr

assert pathlib.Path(cr.__file__).is_relative_to(pathlib.Path(sys.argv[1]).resolve()), cr.__file__
t = np.linspace(-2.0, 2.0, 200)
room = np.r_[np.c_[t, np.full_like(t, 2.0)], np.c_[np.full_like(t, 2.0), -t]]  # two walls and their corner
moved = room - [0.1, 0.0]
result = cr.register(moved, room, method="icp")
assert result.converged and abs(result.pose[0] - 0.1) < 0.01, result
print("python consumer: ok,", cr.__file__)
