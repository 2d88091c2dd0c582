"""The peer for the 1M-row histogram benchmark: pandas reads the CSV, matplotlib's `hist` with
numpy's auto bins draws an 800x500 px PNG. Prints the in-process hist+savefig time to stderr.

Usage: python3 benches/peer_matplotlib_hist.py benches/data/points.csv out.png
"""
import sys
import time

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import pandas as pd  # noqa: E402

df = pd.read_csv(sys.argv[1], usecols=["x"])
start = time.perf_counter()
fig, ax = plt.subplots(figsize=(8, 5), dpi=100)
ax.hist(df["x"], bins="auto")
ax.set_title("One million values")
ax.set_xlabel("x")
ax.set_ylabel("Count")
fig.savefig(sys.argv[2])
print(f"matplotlib hist+savefig in-process: {time.perf_counter() - start:.3f} s", file=sys.stderr)
