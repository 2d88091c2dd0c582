"""Write a wide benchmark table: N rows of k correlated numeric columns c0..c{k-1} plus a class
column, seeded, stdlib only.

Usage: python3 benches/make_table.py benches/data/table_50k.csv 50000 6
"""
import math
import os
import random
import sys

path, n, k = sys.argv[1], int(sys.argv[2]), int(sys.argv[3])
os.makedirs(os.path.dirname(path) or ".", exist_ok=True)
rng = random.Random(1992)
with open(path, "w") as f:
    f.write(",".join(f"c{j}" for j in range(k)) + ",group\n")
    for i in range(n):
        g = i % 3
        base = rng.gauss(g * 1.5, 1.0)
        row = [base * (0.4 + 0.15 * j) + rng.gauss(0.0, 0.5 + 0.1 * j) + math.sin(j + g) for j in range(k)]
        f.write(",".join(f"{v:.4f}" for v in row) + f",g{g}\n")
