"""Write a 512³ u16 volume (256 MB of voxels) as .npy and as uncompressed NIfTI-1, and the spec
that reads both, for the volume load benchmark in README's Performance section:

    python3 benches/make_volume.py            # needs numpy; writes benches/data/volume_512.*
    /usr/bin/time -v target/release/dataink data benches/data/volume.toml ct_npy
    /usr/bin/time -v target/release/dataink data benches/data/volume.toml ct_nii

The NIfTI file is written by hand (a 352-byte header), so nibabel is not needed.
"""

import os
import struct

import numpy as np

N = 512
HERE = os.path.join(os.path.dirname(os.path.abspath(__file__)), "data")


def field():
    # A smooth blob plus a ramp: values 0 to about 60000, different in every voxel row.
    z, y, x = np.ogrid[0:N, 0:N, 0:N]
    c = (N - 1) / 2
    r2 = ((x - c) ** 2 + (y - c) ** 2 + (z - c) ** 2) / c**2
    return (40000 * np.exp(-2 * r2) + 20 * x).astype("<u2")  # shape (z, y, x): x fastest


def nifti_header(shape_xyz, spacing):
    h = bytearray(348)
    struct.pack_into("<i", h, 0, 348)
    struct.pack_into("<8h", h, 40, 3, *shape_xyz, 1, 1, 1, 1)
    struct.pack_into("<hh", h, 70, 512, 16)  # datatype u16, bitpix
    struct.pack_into("<8f", h, 76, 1.0, *spacing, 0, 0, 0, 0)
    struct.pack_into("<f", h, 108, 352.0)  # vox_offset
    struct.pack_into("<ff", h, 112, 1.0, 0.0)  # scl_slope, scl_inter
    h[123] = 2  # mm
    struct.pack_into("<hh", h, 252, 0, 1)  # qform_code 0, sform_code 1
    for row in range(3):
        srow = [0.0, 0.0, 0.0, -spacing[row] * (N - 1) / 2]
        srow[row] = spacing[row]
        struct.pack_into("<4f", h, 280 + 16 * row, *srow)
    h[344:348] = b"n+1\0"
    return bytes(h) + b"\0\0\0\0"


if __name__ == "__main__":
    os.makedirs(HERE, exist_ok=True)
    v = field()
    np.save(os.path.join(HERE, "volume_512.npy"), v)
    with open(os.path.join(HERE, "volume_512.nii"), "wb") as fh:
        fh.write(nifti_header((N, N, N), (0.5, 0.5, 0.8)))
        fh.write(v.tobytes(order="C"))
    with open(os.path.join(HERE, "volume.toml"), "w") as fh:
        fh.write(
            '[data.ct_npy]\npath = "volume_512.npy"\nspacing = [0.5, 0.5, 0.8]\n\n'
            '[data.ct_nii]\npath = "volume_512.nii"\n'
        )
    print("wrote benches/data/volume_512.npy, volume_512.nii and volume.toml")
