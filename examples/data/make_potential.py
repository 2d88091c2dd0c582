"""Write potential.csv: the electric potential of three point charges on a 121 x 101 grid
(long form: x, y, potential), in units of k·q/d. Softened near the charges (r >= 0.15) so the
field stays finite. Stdlib only: python3 examples/data/make_potential.py
"""
import math
import pathlib

charges = [(-1.0, 0.0, 1.0), (1.0, 0.0, 1.0), (0.0, 1.5, -1.5)]


def potential(x, y, z=0.0):
    """Sum of q / r over the charges (all in the z = 0 plane), with r floored at 0.15."""
    return sum(q / max(math.sqrt((x - cx) ** 2 + (y - cy) ** 2 + z * z), 0.15) for cx, cy, q in charges)

out = pathlib.Path(__file__).with_name("potential.csv")
with out.open("w") as f:
    f.write("x,y,potential\n")
    for j in range(101):
        y = -2.0 + 4.5 * j / 100
        for i in range(121):
            x = -3.0 + 6.0 * i / 120
            f.write(f"{x:.4f},{y:.4f},{potential(x, y):.6f}\n")

# The same charges in 3-D space on a 25 x 25 x 25 grid (x, y, z, potential), for the hyperslice.
out3 = pathlib.Path(__file__).with_name("potential3d.csv")
with out3.open("w") as f:
    f.write("x,y,z,potential\n")
    for k in range(25):
        z = -1.5 + 3.0 * k / 24
        for j in range(25):
            y = -2.0 + 4.5 * j / 24
            for i in range(25):
                x = -3.0 + 6.0 * i / 24
                f.write(f"{x:.4f},{y:.4f},{z:.4f},{potential(x, y, z):.6f}\n")
