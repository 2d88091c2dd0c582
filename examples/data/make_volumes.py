"""Copy the two brain volumes of the gallery out of nilearn's wheel (PyPI), unchanged.

- mni152-t1.nii.gz: the ICBM 2009a nonlinear symmetric T1 template (MNI152), 197 × 233 × 189
  voxels of 1 mm, stored as u8, as nilearn ships it (nilearn.datasets.load_mni152_template).
  Copyright (C) 1993-2009 Louis Collins, McConnell Brain Imaging Centre, Montreal Neurological
  Institute, McGill University; permission to use, copy, modify and distribute for any purpose
  and without fee, with this notice kept (http://www.bic.mni.mcgill.ca/ServicesAtlases/ICBM152NLin2009).
- motor-tmap.nii.gz: a t map of the "left vs right button press" contrast, NeuroVault image
  10426 (https://neurovault.org/images/10426/, CC0), 53 × 63 × 46 voxels of 3 mm in MNI space
  (nilearn.datasets.load_sample_motor_activation_image).

Run: python3 examples/data/make_volumes.py  (needs pip and the network to PyPI)
"""

import glob
import pathlib
import subprocess
import sys
import tempfile
import zipfile

HERE = pathlib.Path(__file__).parent
FILES = {
    "nilearn/datasets/data/mni_icbm152_t1_tal_nlin_sym_09a_converted.nii.gz": "mni152-t1.nii.gz",
    "nilearn/datasets/data/image_10426.nii.gz": "motor-tmap.nii.gz",
}

with tempfile.TemporaryDirectory() as tmp:
    subprocess.run(
        [sys.executable, "-m", "pip", "download", "nilearn==0.14.1", "--no-deps", "-q", "-d", tmp], check=True
    )
    wheel = zipfile.ZipFile(glob.glob(f"{tmp}/nilearn-*.whl")[0])
    for inside, name in FILES.items():
        (HERE / name).write_bytes(wheel.read(inside))
        print("wrote", HERE / name)
