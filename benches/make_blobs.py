"""Write benches/data/blobs_256.npy: the 256³ float32 field of four Gaussian blobs,
f = Σ exp(−|p − c|² / 0.02) for p in [0, 1]³ (shape (z, y, x), x fastest), the same field
benches/span_space.rs builds in Rust. Read by benches/volume_256.toml and peer_vtk_volume.py.

Run: python3 benches/make_blobs.py   (needs numpy)
"""
import os

import numpy as np

N = 256
CENTRES = [(0.3, 0.3, 0.3), (0.7, 0.35, 0.6), (0.4, 0.7, 0.45), (0.65, 0.7, 0.25)]
HERE = os.path.join(os.path.dirname(os.path.abspath(__file__)), "data")

a = np.linspace(0.0, 1.0, N)
z, y, x = np.meshgrid(a, a, a, indexing="ij")
f = np.zeros((N, N, N))
for cx, cy, cz in CENTRES:
    f += np.exp(-((x - cx) ** 2 + (y - cy) ** 2 + (z - cz) ** 2) / 0.02)
os.makedirs(HERE, exist_ok=True)
np.save(os.path.join(HERE, "blobs_256.npy"), f.astype(np.float32))
print("wrote", os.path.join(HERE, "blobs_256.npy"))
