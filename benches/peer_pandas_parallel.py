"""Peer for the parallel-coordinates benchmark: pandas' parallel_coordinates to a PNG.

Usage: python3 benches/peer_pandas_parallel.py benches/data/table_20k.csv out.png
"""
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import pandas as pd  # noqa: E402

table = pd.read_csv(sys.argv[1])
plt.figure(figsize=(8.2, 4.4))
pd.plotting.parallel_coordinates(table, "group", alpha=0.1, linewidth=1)
plt.savefig(sys.argv[2], dpi=100)
