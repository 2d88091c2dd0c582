"""Writes the flow examples (long form, one row per grid node and time).

- double-gyre.csv: the time-periodic double gyre of Shadden, Lekien & Marsden (2005) on
  [0, 2] x [0, 1], A = 0.1, eps = 0.25, omega = 2 pi / 10, a 61 x 31 grid at t = 0, 1, ..., 10.
- duffing.csv: the damped Duffing oscillator u = y, v = x - x^3 - 0.3 y on [-2, 2] x [-1.5, 1.5]
  (101 x 76 grid): a saddle at the origin and attracting foci at (+-1, 0) with eigenvalues
  -0.15 +- 1.4062i.

Usage: python3 make_flow.py
"""

import math
from pathlib import Path

out = Path(__file__).parent


def gyre(x, y, t, a=0.1, eps=0.25, omega=2 * math.pi / 10):
    s = eps * math.sin(omega * t)
    f = s * x * x + (1 - 2 * s) * x
    df = 2 * s * x + (1 - 2 * s)
    return (-math.pi * a * math.sin(math.pi * f) * math.cos(math.pi * y),
            math.pi * a * math.cos(math.pi * f) * math.sin(math.pi * y) * df)


with open(out / "double-gyre.csv", "w") as f:
    f.write("x,y,t,u,v\n")
    for t in range(11):
        for j in range(31):
            for i in range(61):
                x, y = 2 * i / 60, j / 30
                u, v = gyre(x, y, t)
                f.write(f"{x:.6g},{y:.6g},{t},{u:.6g},{v:.6g}\n")

with open(out / "duffing.csv", "w") as f:
    f.write("x,y,u,v\n")
    for j in range(76):
        for i in range(101):
            x, y = -2 + 4 * i / 100, -1.5 + 3 * j / 75
            f.write(f"{x:.6g},{y:.6g},{y:.6g},{x - x ** 3 - 0.3 * y:.6g}\n")
