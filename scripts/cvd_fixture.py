#!/usr/bin/env python3
"""Generate tests/fixtures/cvd.json: colour-vision-deficiency simulations by colorspacious.

The Rust tests in src/guide/colour_science.rs check that `simulate_linear` (Machado, Oliveira &
Fernandes 2009, severity 1.0, applied to linear sRGB) matches these values to 1e-9, and that
its matrices are the ones colorspacious ships.

How to run (from the repository root):

    pip install colorspacious numpy
    python3 scripts/cvd_fixture.py            # writes tests/fixtures/cvd.json
    python3 scripts/cvd_fixture.py OUT.json   # or somewhere else

colorspacious converts "sRGB1+CVD" to "sRGB1" by decoding sRGB to linear light, multiplying by
the Machado matrix of the deficiency at the given severity (100 = the paper's dichromat
matrix, used as published) and encoding back to sRGB. The results are NOT clipped to 0..1, so
the fixture also checks out-of-gamut values. The colours are the categorical palettes dataink
ships, the sRGB primaries and secondaries, greys, and random colours from a fixed seed, so the
output is deterministic. Every float is written as a JSON string holding Python's shortest
round-trip repr, which reads back bit-exactly with Rust's `str::parse::<f64>`. The
colorspacious and NumPy versions used are recorded in the file.
"""

import json
import pathlib
import sys

import colorspacious
import numpy as np
from colorspacious import cspace_convert
from colorspacious.cvd import machado_et_al_2009_matrix

SEED = 20090301

PALETTES = {
    "okabe-ito": "0072b2 e69f00 009e73 d55e00 cc79a7 56b4e9 f0e442 000000",
    "category10": "1f77b4 ff7f0e 2ca02c d62728 9467bd 8c564b e377c2 7f7f7f bcbd22 17becf",
    "tableau10": "4e79a7 f28e2b e15759 76b7b2 59a14f edc948 b07aa1 ff9da7 9c755f bab0ab",
    "paired": "a6cee3 1f78b4 b2df8a 33a02c fb9a99 e31a1c fdbf6f ff7f00 cab2d6 6a3d9a ffff99 b15928",
    "set2": "66c2a5 fc8d62 8da0cb e78ac3 a6d854 ffd92f e5c494 b3b3b3",
    "dark2": "1b9e77 d95f02 7570b3 e7298a 66a61e e6ab02 a6761d 666666",
}
EXTRA = "ff0000 00ff00 0000ff ffff00 00ffff ff00ff ffffff 808080 c8c8c8 0a0a0a 010203"

# dataink's names for colorspacious' deficiency types (severity 100: dichromacy).
DEFICIENCIES = {"protanopia": "protanomaly", "deuteranopia": "deuteranomaly"}


def num(x):
    """A float as the string of its shortest round-trip repr."""
    return repr(float(x))


def colours():
    seen = []
    for hexes in PALETTES.values():
        for h in hexes.split():
            if h not in seen:
                seen.append(h)
    for h in EXTRA.split():
        if h not in seen:
            seen.append(h)
    rng = np.random.default_rng(SEED)
    for rgb in rng.integers(0, 256, size=(40, 3)):
        h = "%02x%02x%02x" % tuple(int(v) for v in rgb)
        if h not in seen:
            seen.append(h)
    return seen


def main():
    out = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else "tests/fixtures/cvd.json")
    cases = []
    for h in colours():
        srgb = np.array([int(h[i : i + 2], 16) for i in (0, 2, 4)], dtype=float) / 255.0
        case = {"hex": "#" + h}
        for ours, theirs in DEFICIENCIES.items():
            space = {"name": "sRGB1+CVD", "cvd_type": theirs, "severity": 100}
            case[ours] = [num(v) for v in cspace_convert(srgb, space, "sRGB1")]
        cases.append(case)
    matrices = {
        ours: [[num(v) for v in row] for row in machado_et_al_2009_matrix(theirs, 100)]
        for ours, theirs in DEFICIENCIES.items()
    }
    doc = {
        "generator": "scripts/cvd_fixture.py",
        "colorspacious": colorspacious.__version__,
        "numpy": np.__version__,
        "method": "Machado, Oliveira & Fernandes (2009), severity 1.0, on linear sRGB; output sRGB, unclipped",
        "matrices": matrices,
        "cases": cases,
    }
    # One colour per line, so that a regenerated file diffs line by line.
    head = {k: v for k, v in doc.items() if k != "cases"}
    text = json.dumps(head, indent=1)[:-2] + ',\n "cases": [\n'
    text += ",\n".join("  " + json.dumps(c) for c in cases) + "\n ]\n}\n"
    json.loads(text)
    out.parent.mkdir(parents=True, exist_ok=True)
    out.write_text(text)
    print(f"wrote {len(cases)} colours to {out}")


if __name__ == "__main__":
    main()
