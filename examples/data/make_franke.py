"""Write franke.csv: Franke's (1979) scattered-data test function sampled at 150 points of the
2-D Halton sequence (bases 2 and 3) on the unit square. Stdlib only:
python3 examples/data/make_franke.py
"""
import math
import pathlib


def halton(i, base):
    f, r = 1.0, 0.0
    while i > 0:
        f /= base
        r += f * (i % base)
        i //= base
    return r


def franke(x, y):
    return (0.75 * math.exp(-((9 * x - 2) ** 2) / 4 - ((9 * y - 2) ** 2) / 4)
            + 0.75 * math.exp(-((9 * x + 1) ** 2) / 49 - (9 * y + 1) / 10)
            + 0.5 * math.exp(-((9 * x - 7) ** 2) / 4 - ((9 * y - 3) ** 2) / 4)
            - 0.2 * math.exp(-((9 * x - 4) ** 2) - (9 * y - 7) ** 2))


out = pathlib.Path(__file__).with_name("franke.csv")
with out.open("w") as f:
    f.write("x,y,f\n")
    for i in range(1, 151):
        x, y = halton(i, 2), halton(i, 3)
        f.write(f"{x:.6f},{y:.6f},{franke(x, y):.6f}\n")

# The same function on a regular 41 x 41 grid (long form), for the surface view.
grid = pathlib.Path(__file__).with_name("franke-grid.csv")
with grid.open("w") as f:
    f.write("x,y,f\n")
    for j in range(41):
        for i in range(41):
            x, y = i / 40, j / 40
            f.write(f"{x:.3f},{y:.3f},{franke(x, y):.6f}\n")

# The same function as a 2-D NumPy array (rows along y) for the grid-file reader; needs numpy.
try:
    import numpy as np

    xs = np.linspace(0.0, 1.0, 61)
    X, Y = np.meshgrid(xs, xs)
    np.save(pathlib.Path(__file__).with_name("franke.npy"), np.vectorize(franke)(X, Y))
except ImportError:
    print("numpy not installed: franke.npy not rewritten")
