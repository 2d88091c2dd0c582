"""Peer for the splom benchmark: pandas' scatter_matrix of every numeric column to a PNG.

Usage: python3 benches/peer_pandas_splom.py benches/data/table_50k.csv out.png
"""
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import pandas as pd  # noqa: E402

table = pd.read_csv(sys.argv[1])
pd.plotting.scatter_matrix(table.drop(columns="group"), figsize=(8, 8), alpha=0.2, s=2, diagonal="hist")
plt.savefig(sys.argv[2], dpi=100)
