"""Write the flow benchmark's data: the double gyre (Shadden, Lekien & Marsden 2005) at t = 0 on
[0, 2] x [0, 1], sampled on an N x N grid of nodes. Needs numpy (pip install numpy).

    A = 0.1, eps = 0.25, omega = 2 pi / 10
    f(x, t) = eps sin(omega t) x^2 + (1 - 2 eps sin(omega t)) x
    u = -pi A sin(pi f) cos(pi y),   v = pi A cos(pi f) sin(pi y) df/dx

The CSV is long form with header x,y,u,v, one row per node, x varying fastest. With --npy it
also writes gyre_1024_u.npy and gyre_1024_v.npy (1024 x 1024 float64, row j = y index) next to
the CSV.

Usage: python3 benches/make_flow.py benches/data/gyre_512.csv 512 [--npy]
"""
import os
import sys

import numpy as np

A, EPS, OMEGA = 0.1, 0.25, 2.0 * np.pi / 10.0


def gyre(n, t=0.0):
    """Axes x (n), y (n) and components u, v (n x n, row j = y[j]) of the double gyre at time t."""
    x = np.linspace(0.0, 2.0, n)
    y = np.linspace(0.0, 1.0, n)
    xx, yy = np.meshgrid(x, y)
    a = EPS * np.sin(OMEGA * t)
    f = a * xx * xx + (1.0 - 2.0 * a) * xx
    dfdx = 2.0 * a * xx + (1.0 - 2.0 * a)
    u = -np.pi * A * np.sin(np.pi * f) * np.cos(np.pi * yy)
    v = np.pi * A * np.cos(np.pi * f) * np.sin(np.pi * yy) * dfdx
    return x, y, u, v


def main():
    args = [a for a in sys.argv[1:] if a != "--npy"]
    if len(args) != 2:
        sys.exit(__doc__)
    path, n = args[0], int(args[1])
    out_dir = os.path.dirname(path) or "."
    os.makedirs(out_dir, exist_ok=True)
    x, y, u, v = gyre(n)
    xx, yy = np.meshgrid(x, y)
    table = np.column_stack([xx.ravel(), yy.ravel(), u.ravel(), v.ravel()])
    np.savetxt(path, table, fmt="%.10g", delimiter=",", header="x,y,u,v", comments="")
    if "--npy" in sys.argv[1:]:
        _, _, u1, v1 = gyre(1024)
        np.save(os.path.join(out_dir, "gyre_1024_u.npy"), u1)
        np.save(os.path.join(out_dir, "gyre_1024_v.npy"), v1)


if __name__ == "__main__":
    main()
