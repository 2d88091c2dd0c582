"""A 2000 x 2000 float64 .npy grid (the field of `cargo bench --bench contour`) for the whole-process
contour benchmark. Usage: python3 benches/make_grid_npy.py benches/data/grid_2000.npy [n]"""
import sys

import numpy as np

path = sys.argv[1]
n = int(sys.argv[2]) if len(sys.argv) > 2 else 2000
axis = np.linspace(-3.0, 3.0, n)
x, y = np.meshgrid(axis, axis)
z = np.sin(1.7 * x) * np.cos(1.3 * y) + 0.2 * (x * x - y * y) + 0.1 * x * y + 0.2
np.save(path, z)
