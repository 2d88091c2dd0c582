"""Write the gallery's synthetic volumes as .npy arrays (shape (nz, ny, nx), x fastest).

- marschner-lobb.npy: the Marschner–Lobb test signal (Marschner & Lobb 1994, "An evaluation of
  reconstruction filters for volume rendering"), f_M = 6, alpha = 0.25, sampled at 41^3 on
  [-1, 1]^3 (spacing 0.05, origin -1): a signal near the Nyquist limit, the usual test of how
  an isosurface or a volume renderer reconstructs a field between samples.
- hydrogen-3dz2.npy: the electron density |psi|^2 of hydrogen's 3d_z2 orbital,
  psi ~ r^2 exp(-r / 3) (3 cos^2 theta - 1) in Bohr radii, on [-24, 24]^3 at 49^3 (spacing 1,
  origin -24), scaled so its maximum is 1: two lobes along z and a torus around them.

Run: python3 examples/data/make_fields.py  (needs numpy)
"""

import pathlib

import numpy as np

HERE = pathlib.Path(__file__).parent


def marschner_lobb(n=41, f_m=6.0, alpha=0.25):
    t = np.linspace(-1.0, 1.0, n)
    z, y, x = np.meshgrid(t, t, t, indexing="ij")
    r = np.sqrt(x * x + y * y)
    rho = np.cos(2.0 * np.pi * f_m * np.cos(np.pi * r / 2.0))
    return ((1.0 - np.sin(np.pi * z / 2.0) + alpha * (1.0 + rho)) / (2.0 * (1.0 + alpha))).astype(np.float32)


def hydrogen_3dz2(n=49, half=24.0):
    t = np.linspace(-half, half, n)
    z, y, x = np.meshgrid(t, t, t, indexing="ij")
    r2 = x * x + y * y + z * z
    psi = np.exp(-np.sqrt(r2) / 3.0) * (3.0 * z * z - r2)  # r^2 (3 cos^2 theta - 1)
    density = psi * psi
    return (density / density.max()).astype(np.float32)


np.save(HERE / "marschner-lobb.npy", marschner_lobb())
np.save(HERE / "hydrogen-3dz2.npy", hydrogen_3dz2())
print("wrote", HERE / "marschner-lobb.npy", HERE / "hydrogen-3dz2.npy")
