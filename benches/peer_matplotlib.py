"""The peer for the 1M-point scatter benchmark: pandas reads the CSV, matplotlib draws a
1000x1000 px PNG. Prints the in-process scatter+savefig time (seconds) to stderr.

Usage: python3 benches/peer_matplotlib.py benches/data/points.csv out.png
"""
import sys
import time

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import pandas as pd  # noqa: E402

df = pd.read_csv(sys.argv[1])
start = time.perf_counter()
fig, ax = plt.subplots(figsize=(10, 10), dpi=100)
ax.scatter(df["x"], df["y"], s=1, alpha=0.2, linewidths=0)
ax.set_xlabel("x")
ax.set_ylabel("y")
fig.savefig(sys.argv[2])
print(f"matplotlib scatter+savefig in-process: {time.perf_counter() - start:.3f} s", file=sys.stderr)
