"""Write the NIfTI-1 fixtures of tests/data/volume/ with nibabel, and expected.json: for each file,
what nibabel reads from it (shape, voxel values after scl_slope/scl_inter, img.affine, zooms,
unit), which the Rust reader must match voxel for voxel.

    pip install nibabel numpy && python3 tests/data/volume/make_fixtures.py

Fixtures (all tiny, known values f(i, j, k) = i + 10 j + 100 k, i along x):
- le_sform_i16.nii   little-endian i16, sform (code 2) with a rotation and offset, qform too
                     (the sform wins), scl_slope 0.5 / scl_inter -3, unit mm
- le_sform_i16.nii.gz  the same, gzip-compressed
- be_qform_f32.nii   big-endian f32 with a NaN voxel, qform only (code 1, rotation, qfac -1), unit µm
- be_qform_f32.nii.gz  the same, gzip-compressed
- u16_noform.nii     little-endian u16, both codes 0: the affine is the spacing alone
- u8_4d.nii          4-D u8, 3 volumes (frame n holds f + n)
- pair_u8.hdr/.img   a NIfTI-1 pair (magic ni1)
"""

import gzip
import json
import math
import os
import shutil
import struct

import nibabel as nib
import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
SHAPE = (4, 3, 2)  # x, y, z


def f(shape=SHAPE):
    i, j, k = np.indices(shape)
    return i + 10 * j + 100 * k


def patch_scaling(path, slope, inter):
    """Set scl_slope / scl_inter in the header bytes (nibabel resets them when it writes ints)."""
    with open(path, "r+b") as fh:
        head = fh.read(4)
        order = "<" if struct.unpack("<i", head)[0] == 348 else ">"
        fh.seek(112)
        fh.write(struct.pack(order + "ff", slope, inter))


def gz(path):
    with open(path, "rb") as src, gzip.open(path + ".gz", "wb", compresslevel=9) as dst:
        shutil.copyfileobj(src, dst)


def rotation(angle_deg):
    a = math.radians(angle_deg)
    c, s = math.cos(a), math.sin(a)
    return np.array([[c, -s, 0], [s, c, 0], [0, 0, 1.0]])


def write_all():
    files = []

    # Little-endian i16 with an sform (wins over the qform) and scaling.
    data = f().astype("<i2")
    sform = np.eye(4)
    sform[:3, :3] = rotation(30) @ np.diag([0.8, 1.2, 2.5])
    sform[:3, 3] = [-10.0, 20.5, 3.25]
    img = nib.Nifti1Image(data, sform)
    img.header.set_sform(sform, code=2)
    img.header.set_qform(np.diag([2.0, 2.0, 2.0, 1.0]), code=1)
    img.header.set_xyzt_units("mm", "sec")
    path = os.path.join(HERE, "le_sform_i16.nii")
    nib.save(img, path)
    patch_scaling(path, 0.5, -3.0)
    gz(path)
    files += ["le_sform_i16.nii", "le_sform_i16.nii.gz"]

    # Big-endian f32 with a NaN voxel, qform only, qfac -1.
    data = f().astype(">f4")
    data[1, 2, 1] = np.nan
    hdr = nib.Nifti1Header(endianness=">")
    qform = np.eye(4)
    qform[:3, :3] = rotation(-90) @ np.diag([1.5, 0.5, -2.0])  # det < 0: qfac -1
    qform[:3, 3] = [5.0, -7.0, 11.0]
    img = nib.Nifti1Image(data, None, header=hdr)
    img.header.set_qform(qform, code=1)
    img.header.set_sform(None, code=0)
    img.header.set_xyzt_units("micron")
    path = os.path.join(HERE, "be_qform_f32.nii")
    nib.save(img, path)
    gz(path)
    files += ["be_qform_f32.nii", "be_qform_f32.nii.gz"]

    # u16, no qform or sform.
    data = (f() * 300).astype("<u2")
    img = nib.Nifti1Image(data, None)
    img.header.set_qform(None, code=0)
    img.header.set_sform(None, code=0)
    img.header.set_zooms((0.25, 0.5, 4.0))
    path = os.path.join(HERE, "u16_noform.nii")
    nib.save(img, path)
    files += ["u16_noform.nii"]

    # 4-D u8: frame n is f + n.
    data = np.stack([f() + n for n in range(3)], axis=-1).astype("u1")
    img = nib.Nifti1Image(data, np.diag([1.0, 1.0, 1.0, 1.0]))
    path = os.path.join(HERE, "u8_4d.nii")
    nib.save(img, path)
    files += ["u8_4d.nii"]

    # A .hdr/.img pair.
    data = f().astype("u1")
    img = nib.Nifti1Pair(data, np.diag([3.0, 2.0, 1.0, 1.0]))
    nib.save(img, os.path.join(HERE, "pair_u8.img"))
    files += ["pair_u8.hdr"]
    return files


def expected(files):
    out = {}
    for name in files:
        img = nib.load(os.path.join(HERE, name))
        data = np.asanyarray(img.dataobj, dtype=np.float64)
        if data.ndim == 4:
            data = data[..., 0]
        units = img.header.get_xyzt_units()[0]
        out[name] = {
            "dims": list(data.shape),
            "dtype": str(img.get_data_dtype().newbyteorder("=")),
            # Voxel values x fastest (Fortran order of the [i, j, k] array); NaN as null.
            "values": [None if math.isnan(v) else v for v in data.flatten(order="F").tolist()],
            "affine": img.affine[:3].tolist(),
            "zooms": [float(z) for z in img.header.get_zooms()[:3]],
            "unit": units,
        }
    return out


if __name__ == "__main__":
    names = write_all()
    with open(os.path.join(HERE, "expected.json"), "w") as fh:
        json.dump(expected(names), fh, indent=1)
        fh.write("\n")
    print("wrote", ", ".join(names), "and expected.json")
