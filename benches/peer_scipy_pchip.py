"""SciPy peer of `cargo bench --bench interp`: PCHIP with 1,000 knots, 10,000,000 evaluations.

Usage: python3 benches/peer_scipy_pchip.py   (pip install numpy scipy)
"""
import time

import numpy as np
from scipy.interpolate import PchipInterpolator

i = np.arange(1000)
x = i + 0.3 * ((i * 7919 % 13) / 13.0)
y = np.sin(x * 0.05) + 0.01 * x
curve = PchipInterpolator(x, y)
ts = np.linspace(x[0], x[-1], 10_000_000)
best = float("inf")
for _ in range(5):
    start = time.perf_counter()
    curve(ts)
    best = min(best, time.perf_counter() - start)
print(f"scipy PchipInterpolator, 1000 knots, 1e7 evaluations: best of 5 = {best:.4f} s")
