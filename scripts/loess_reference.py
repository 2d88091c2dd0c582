"""Known answers for src/enrich/regression.rs: statsmodels' lowess (it=0, no robustness
iterations; delta=0) of Miles_per_Gallon on Horsepower in examples/data/cars.json, span 0.5, at
the first ten cars with both values (in file order), and numpy's least-squares line.

Run: python3 scripts/loess_reference.py (needs numpy and statsmodels).
"""
import json

import numpy as np
from statsmodels.nonparametric.smoothers_lowess import lowess

cars = json.load(open("examples/data/cars.json"))
pairs = [(c["Horsepower"], c["Miles_per_Gallon"]) for c in cars
         if c["Horsepower"] is not None and c["Miles_per_Gallon"] is not None]
x = np.array([p[0] for p in pairs], dtype=float)
y = np.array([p[1] for p in pairs], dtype=float)
fitted = lowess(y, x, frac=0.5, it=0, delta=0.0, return_sorted=False)
print("n", len(x))
print("x[:10]", x[:10].tolist())
print("lowess[:10]", [round(v, 10) for v in fitted[:10].tolist()])
slope, intercept = np.polyfit(x, y, 1)
r2 = np.corrcoef(x, y)[0, 1] ** 2
print("linear", slope, intercept, r2)
