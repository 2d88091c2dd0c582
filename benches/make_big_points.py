"""Write the large-data benchmark's points: N rows of two float32 columns (x, y) in a Parquet
file, seeded, written one row group of a million rows at a time (memory stays small for 10⁹ rows).

The points are five Gaussian clusters of very different spreads and sizes, a thin ring and a
sparse uniform background, so a density view needs its whole range of counts: millions of rows
in some bins, one in others.

Usage: python3 benches/make_big_points.py benches/data/points_1e8.parquet 100000000
Needs numpy and pyarrow (pip install numpy pyarrow).
"""
import os
import sys

import numpy as np
import pyarrow as pa
import pyarrow.parquet as pq

GROUP = 1_000_000
# (share of the rows, centre x, centre y, spread x, spread y, correlation)
CLUSTERS = [
    (0.40, -2.0, -1.0, 0.9, 0.6, 0.3),
    (0.25, 1.5, 2.0, 0.35, 0.35, 0.0),
    (0.15, 3.0, -2.5, 1.4, 0.5, -0.6),
    (0.08, -3.5, 3.0, 0.12, 0.12, 0.0),
    (0.05, 0.5, 0.0, 1.2, 0.08, 0.0),
]
RING = 0.05  # share on a ring of radius 4.5 around the origin
# The rest is uniform over [-8, 8]².


def group(rng, n):
    kind = rng.random(n)
    x = np.empty(n, dtype=np.float64)
    y = np.empty(n, dtype=np.float64)
    start = 0.0
    for share, cx, cy, sx, sy, rho in CLUSTERS:
        pick = (kind >= start) & (kind < start + share)
        k = int(pick.sum())
        a, b = rng.standard_normal(k), rng.standard_normal(k)
        x[pick] = cx + sx * a
        y[pick] = cy + sy * (rho * a + np.sqrt(1.0 - rho * rho) * b)
        start += share
    pick = (kind >= start) & (kind < start + RING)
    k = int(pick.sum())
    angle = rng.random(k) * 2.0 * np.pi
    radius = 4.5 + 0.05 * rng.standard_normal(k)
    x[pick], y[pick] = radius * np.cos(angle), radius * np.sin(angle)
    start += RING
    pick = kind >= start
    k = int(pick.sum())
    x[pick], y[pick] = rng.uniform(-8, 8, k), rng.uniform(-8, 8, k)
    return x.astype(np.float32), y.astype(np.float32)


def main():
    path, n = sys.argv[1], int(float(sys.argv[2]))
    os.makedirs(os.path.dirname(path) or ".", exist_ok=True)
    rng = np.random.default_rng(20261207)
    schema = pa.schema([("x", pa.float32()), ("y", pa.float32())])
    with pq.ParquetWriter(path + ".part", schema, compression="snappy") as writer:
        done = 0
        while done < n:
            k = min(GROUP, n - done)
            x, y = group(rng, k)
            writer.write_table(pa.table({"x": x, "y": y}, schema=schema), row_group_size=GROUP)
            done += k
    os.replace(path + ".part", path)


if __name__ == "__main__":
    main()
