"""contourpy peer of `cargo bench --bench contour`: the same 2000x2000 field and 10 nice levels.

Usage: python3 benches/peer_contourpy.py   (pip install numpy contourpy)
"""
import time

import contourpy
import numpy as np

n = 2000
axis = np.linspace(-3.0, 3.0, n)
x, y = np.meshgrid(axis, axis)
z = np.sin(1.7 * x) * np.cos(1.3 * y) + 0.2 * (x * x - y * y) + 0.1 * x * y + 0.2
lo, hi = float(z.min()), float(z.max())
levels = [l for l in np.arange(-2.0, 3.0, 0.5) if lo < l < hi]  # the 10 nice levels dataink picks
edges = [lo] + levels + [hi]


def best_of(fn, runs=5):
    best = float("inf")
    for _ in range(runs):
        start = time.perf_counter()
        fn()
        best = min(best, time.perf_counter() - start)
    return best


def lines():
    gen = contourpy.contour_generator(axis, axis, z, name="serial")
    for level in levels:
        gen.lines(level)


def bands():
    gen = contourpy.contour_generator(axis, axis, z, name="serial")
    for a, b in zip(edges[:-1], edges[1:]):
        gen.filled(a, b)


print(f"levels: {levels}")
print(f"contourpy serial lines: best of 5 = {best_of(lines):.4f} s")
print(f"contourpy serial filled: best of 5 = {best_of(bands):.4f} s")
