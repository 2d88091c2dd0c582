"""The peer for the flow benchmark: pandas reads the long-form x,y,u,v CSV (x fastest), matplotlib
draws streamlines with streamplot(density=2) on a 1000x500 px PNG. Prints the in-process
streamplot+savefig time (seconds) to stderr.

Usage: python3 benches/peer_matplotlib_streamplot.py benches/data/gyre_512.csv out.png
"""
import sys
import time

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import pandas as pd  # noqa: E402

df = pd.read_csv(sys.argv[1])
nx = int((df["y"] == df["y"].iloc[0]).sum())
ny = len(df) // nx
x = df["x"].to_numpy()[:nx]
y = df["y"].to_numpy()[::nx]
u = df["u"].to_numpy().reshape(ny, nx)
v = df["v"].to_numpy().reshape(ny, nx)
start = time.perf_counter()
fig, ax = plt.subplots(figsize=(10, 5), dpi=100)
ax.streamplot(x, y, u, v, density=2)
ax.set_title("Double gyre, 512 × 512 grid")
ax.set_xlabel("x")
ax.set_ylabel("y")
fig.savefig(sys.argv[2])
print(f"matplotlib streamplot+savefig in-process: {time.perf_counter() - start:.3f} s", file=sys.stderr)
