"""The peer for the density benchmark: datashader + pandas reading the same Parquet file, counting
its points into a 1000 × 1000 grid, shading it (eq_hist, datashader's default) and writing a PNG.

Usage: python3 benches/peer_datashader.py benches/data/points_1e8.parquet /tmp/peer.png
Needs pandas, pyarrow and datashader (pip install pandas pyarrow datashader).
"""
import sys

import datashader as ds
import datashader.transfer_functions as tf
import pandas as pd


def main():
    path, out = sys.argv[1], sys.argv[2]
    frame = pd.read_parquet(path, columns=["x", "y"])
    canvas = ds.Canvas(plot_width=1000, plot_height=1000)
    counts = canvas.points(frame, "x", "y", agg=ds.count())
    image = tf.shade(counts, how="eq_hist")
    image.to_pil().save(out)


if __name__ == "__main__":
    main()
