"""Peer of benches/contour_npy.toml as a whole process: np.load the .npy grid and run contourpy
(serial) for the same 10 nice levels, lines and filled bands. Writes nothing.

Usage: python3 benches/peer_contourpy_npy.py benches/data/grid_2000.npy [--lines-only]
(pip install numpy contourpy); --lines-only skips the bands (peer of benches/contour_npy_lines.toml).
"""
import sys

import contourpy
import numpy as np

z = np.load(sys.argv[1])
ny, nx = z.shape
x = np.linspace(-3.0, 3.0, nx)
y = np.linspace(-3.0, 3.0, ny)
lo, hi = float(z.min()), float(z.max())
levels = [l for l in np.arange(-2.0, 3.0, 0.5) if lo < l < hi]
edges = [lo] + levels + [hi]
gen = contourpy.contour_generator(x, y, z, name="serial")
lines = [gen.lines(level) for level in levels]
if "--lines-only" not in sys.argv:
    bands = [gen.filled(a, b) for a, b in zip(edges[:-1], edges[1:])]
