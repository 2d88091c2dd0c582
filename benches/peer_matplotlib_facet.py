"""The peer for the faceted 1M-point scatter benchmark, as seaborn's FacetGrid does it: pandas
reads the CSV, matplotlib draws one subplot per value of `panel` (4 columns, shared axes, outer
tick labels only) and writes a 1600x1000 px PNG. Prints the in-process plotting time to stderr.

Usage: python3 benches/peer_matplotlib_facet.py benches/data/points.csv out.png
"""
import math
import sys
import time

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import pandas as pd  # noqa: E402

df = pd.read_csv(sys.argv[1])
start = time.perf_counter()
groups = sorted(df["panel"].unique())
ncols = math.ceil(math.sqrt(len(groups)))
nrows = math.ceil(len(groups) / ncols)
fig, axes = plt.subplots(nrows, ncols, figsize=(16, 10), dpi=100, sharex=True, sharey=True, squeeze=False)
for ax, (name, part) in zip(axes.flat, df.groupby("panel", sort=True)):
    ax.scatter(part["x"], part["y"], s=1, alpha=0.2, linewidths=0)
    ax.set_title(f"panel = {name}")
for ax in axes.flat[len(groups):]:
    ax.set_visible(False)
fig.supxlabel("x")
fig.supylabel("y")
fig.suptitle("One million points in ten panels")
fig.savefig(sys.argv[2])
print(f"matplotlib subplots+savefig in-process: {time.perf_counter() - start:.3f} s", file=sys.stderr)
