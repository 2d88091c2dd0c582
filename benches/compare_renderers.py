"""Pixel differences between the images of benches/renderers.toml: shear-warp and the default
ray cast, each against the fine ray-cast reference, over the pixels either image draws on (the
caption left out). Differences are the largest of the three channels, in 8-bit levels.

Usage: python3 benches/compare_renderers.py OUT_DIR   (pip install numpy pillow)
"""
import sys

import numpy as np
from PIL import Image

PAIRS = [("sw", "rc-fine"), ("rc-after", "rc-fine"), ("mni-sw", "mni-rc-fine"), ("mni-rc", "mni-rc-fine")]


def load(out, name):
    return np.asarray(Image.open(f"{out}/{name}.png").convert("RGB")).astype(float)


def main():
    out = sys.argv[1]
    for a, b in PAIRS:
        image, reference = load(out, a), load(out, b)
        keep = int(image.shape[0] * 0.9)
        image, reference = image[:keep], reference[:keep]
        drawn = (image.min(axis=2) < 250) | (reference.min(axis=2) < 250)
        d = np.abs(image - reference).max(axis=2)[drawn]
        print(
            f"{a} vs {b}: {drawn.sum()} pixels drawn, mean {d.mean():.2f} levels, "
            f"99th percentile {np.percentile(d, 99):.0f}, largest {d.max():.0f}, over 8 levels {(d > 8).mean() * 100:.1f}%"
        )


main()
