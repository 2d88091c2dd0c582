"""Known answers for src/enrich/histogram.rs: numpy's bin rules and counts on iris sepal lengths.

Run: python3 scripts/histogram_reference.py (needs numpy).
"""
import csv
import numpy as np

with open("examples/data/iris.csv") as f:
    x = np.array([float(r["sepal_length"]) for r in csv.DictReader(f)])
print("values", len(x), x.tolist())
for bins in ["fd", "sturges", "auto", 10]:
    counts, edges = np.histogram(x, bins=bins)
    print(bins, len(counts), counts.tolist())
print("edges 0..1/10", np.linspace(0, 1, 11).tolist())
