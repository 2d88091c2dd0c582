"""Write the gallery's synthetic volumes as .npy arrays (shape (nz, ny, nx), x fastest).

- marschner-lobb.npy: the Marschner–Lobb test signal (Marschner & Lobb 1994, "An evaluation of
  reconstruction filters for volume rendering"), f_M = 6, alpha = 0.25, sampled at 41^3 on
  [-1, 1]^3 (spacing 0.05, origin -1): a signal near the Nyquist limit, the usual test of how
  an isosurface or a volume renderer reconstructs a field between samples.
- hydrogen-3dz2.npy: the electron density |psi|^2 of hydrogen's 3d_z2 orbital,
  psi ~ r^2 exp(-r / 3) (3 cos^2 theta - 1) in Bohr radii, on [-24, 24]^3 at 49^3 (spacing 1,
  origin -24), scaled so its maximum is 1: two lobes along z and a torus around them.
- shepp-logan.npy.gz and shepp-logan-labels.npy.gz: the 3-D Shepp-Logan head phantom, ten
  ellipsoids on [-1, 1]^3 at 129^3 (spacing 1/64, origin -1), with the parameters of the
  modified 3-D phantom as tabulated after Kak & Slaney (1988), each ellipsoid turned about z
  only. The first holds the intensity (the sum of the ellipsoids' densities containing a voxel,
  times 100, as uint8): skull 100, brain 20, ventricles 0, tumours 30 and more where they
  overlap. The second labels each voxel by the innermost ellipsoid holding it (uint8): 0 outside,
  1 skull, 2 brain, 3 right ventricle, 4 left ventricle, 5 the large tumour, 6 the small ones.
- bucky-ball.npy.gz: a "bucky ball": Gaussians (sigma 0.06) centred on the 60 vertices of a
  truncated icosahedron of radius 0.7 (the carbon atoms of C60), on [-1, 1]^3 at 65^3, scaled
  to 0..255 as uint8.

Run: python3 examples/data/make_fields.py  (needs numpy)
"""

import gzip
import itertools
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


# A, semi-axes a b c, centre x0 y0 z0, turn about z in degrees; the label each ellipsoid gives.
SHEPP_LOGAN = [
    (1.0, 0.6900, 0.920, 0.810, 0.00, 0.0000, 0.00, 0.0, 1),
    (-0.8, 0.6624, 0.874, 0.780, 0.00, -0.0184, 0.00, 0.0, 2),
    (-0.2, 0.1100, 0.310, 0.220, 0.22, 0.0000, 0.00, -18.0, 3),
    (-0.2, 0.1600, 0.410, 0.280, -0.22, 0.0000, 0.00, 18.0, 4),
    (0.1, 0.2100, 0.250, 0.410, 0.00, 0.3500, -0.15, 0.0, 5),
    (0.1, 0.0460, 0.046, 0.050, 0.00, 0.1000, 0.25, 0.0, 6),
    (0.1, 0.0460, 0.046, 0.050, 0.00, -0.1000, 0.25, 0.0, 6),
    (0.1, 0.0460, 0.023, 0.050, -0.08, -0.6050, 0.00, 0.0, 6),
    (0.1, 0.0230, 0.023, 0.020, 0.00, -0.6060, 0.00, 0.0, 6),
    (0.1, 0.0230, 0.046, 0.020, 0.06, -0.6050, 0.00, 0.0, 6),
]


def shepp_logan(n=129):
    t = np.linspace(-1.0, 1.0, n)
    z, y, x = np.meshgrid(t, t, t, indexing="ij")
    density = np.zeros(x.shape)
    labels = np.zeros(x.shape, dtype=np.uint8)
    for amp, a, b, c, x0, y0, z0, turn, label in SHEPP_LOGAN:
        cos, sin = np.cos(np.radians(turn)), np.sin(np.radians(turn))
        u, v = (x - x0) * cos + (y - y0) * sin, -(x - x0) * sin + (y - y0) * cos
        inside = (u / a) ** 2 + (v / b) ** 2 + ((z - z0) / c) ** 2 <= 1.0
        density[inside] += amp
        labels[inside] = label
    return np.round(density * 100.0).clip(0, 255).astype(np.uint8), labels


def truncated_icosahedron():
    phi = (1.0 + 5.0**0.5) / 2.0
    bases = [(0.0, 1.0, 3.0 * phi), (1.0, 2.0 + phi, 2.0 * phi), (phi, 2.0, 2.0 * phi + 1.0)]
    even = [(0, 1, 2), (1, 2, 0), (2, 0, 1)]
    points = set()
    for base in bases:
        for signs in itertools.product((1.0, -1.0), repeat=3):
            signed = [b * s for b, s in zip(base, signs)]
            for p in even:
                points.add(tuple(round(signed[i], 9) for i in p))
    assert len(points) == 60, len(points)
    return np.array(sorted(points))


def bucky_ball(n=65, radius=0.7, sigma=0.06):
    atoms = truncated_icosahedron()
    atoms *= radius / np.linalg.norm(atoms[0])
    t = np.linspace(-1.0, 1.0, n)
    z, y, x = np.meshgrid(t, t, t, indexing="ij")
    field = np.zeros(x.shape)
    for ax, ay, az in atoms:
        field += np.exp(-((x - ax) ** 2 + (y - ay) ** 2 + (z - az) ** 2) / (2.0 * sigma * sigma))
    return np.round(255.0 * field / field.max()).astype(np.uint8)


def save_gz(name, array):
    # mtime 0: the same bytes on every run.
    with open(HERE / name, "wb") as raw, gzip.GzipFile(fileobj=raw, mode="wb", mtime=0) as out:
        np.save(out, array)


np.save(HERE / "marschner-lobb.npy", marschner_lobb())
np.save(HERE / "hydrogen-3dz2.npy", hydrogen_3dz2())
density, labels = shepp_logan()
save_gz("shepp-logan.npy.gz", density)
save_gz("shepp-logan-labels.npy.gz", labels)
save_gz("bucky-ball.npy.gz", bucky_ball())
print("wrote the marschner-lobb, hydrogen-3dz2, shepp-logan, shepp-logan-labels and bucky-ball volumes")
