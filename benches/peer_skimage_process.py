"""The peer of `dataink render benches/volume_256.toml --chart blobs-surface` as a whole
process: NumPy loads benches/data/blobs_256.npy and scikit-image's `measure.marching_cubes`
extracts the level 0.5 (with its normals), and nothing is drawn. Timed with hyperfine beside
dataink (see benches/volume_256.toml).

Usage: python3 benches/peer_skimage_process.py   (pip install numpy scikit-image)
"""
import os

import numpy as np
from skimage import measure

HERE = os.path.join(os.path.dirname(os.path.abspath(__file__)), "data")

volume = np.load(os.path.join(HERE, "blobs_256.npy"))
verts, faces, normals, values = measure.marching_cubes(volume, 0.5)
print(len(verts), "vertices,", len(faces), "triangles")
