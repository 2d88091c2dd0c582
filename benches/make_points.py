"""Write the benchmark's scatter data: N rows of (x, y, group, panel), seeded, stdlib only
(`panel`, p0 to p9, splits the rows into ten facet panels).

Usage: python3 benches/make_points.py benches/data/points.csv 1000000
"""
import math
import os
import random
import sys

path, n = sys.argv[1], int(sys.argv[2])
os.makedirs(os.path.dirname(path) or ".", exist_ok=True)
rng = random.Random(20101)
centres = [(-2.0, -1.0, 0.9), (1.5, 2.0, 0.6), (3.0, -2.5, 1.2)]
with open(path, "w") as f:
    f.write("x,y,group,panel\n")
    for i in range(n):
        cx, cy, s = centres[i % 3]
        r = s * math.sqrt(-2.0 * math.log(1.0 - rng.random()))
        a = 2.0 * math.pi * rng.random()
        f.write(f"{cx + r * math.cos(a):.5f},{cy + r * math.sin(a):.5f},g{i % 3},p{i % 10}\n")
