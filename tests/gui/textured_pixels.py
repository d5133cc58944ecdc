#!/usr/bin/env python3
"""textured_pixels.py MATERIAL.png SOLID.png CX CY

Compares a Material and a Solid screenshot of one view in the 400 × 300 px box around (CX, CY) (an object's centre
in pixels, from the GUI probe). Of the pixels that differ between the two (by more than 60 in R+G+B), Solid draws
most in one 30° hue sector: the object colour. Where Material draws the object's textures, almost none of those
pixels keep that hue. Prints "changed solid_share material_share" (the shares of Solid's dominant sector, in %).
Reads the PNGs with Pillow into NumPy arrays (read_rgb is shared with the other GUI tests that look at pixels:
shading.sh).
"""
import sys

import numpy as np
from PIL import Image


def read_rgb(path):
    """The PNG at PATH as an H × W × 3 int32 array (8-bit R, G, B; alpha dropped)."""
    with Image.open(path) as im:
        return np.asarray(im.convert("RGB"), dtype=np.int32)


def sectors(rgb):
    """The 30° hue sector (0-11) of each pixel of an N × 3 array; -1 where saturation < 0.15 or value < 0.1
    (colorsys.rgb_to_hsv's hue, vectorised)."""
    c = rgb.astype(np.float64) / 255
    r, g, b = c[:, 0], c[:, 1], c[:, 2]
    mx, mn = c.max(axis=1), c.min(axis=1)
    span = np.where(mx > mn, mx - mn, 1)
    rc, gc, bc = (mx - r) / span, (mx - g) / span, (mx - b) / span
    hue = np.where(r == mx, bc - gc, np.where(g == mx, 2.0 + rc - bc, 4.0 + gc - rc))
    hue = np.where(mx > mn, (hue / 6.0) % 1.0, 0.0)
    s = np.where(mx > 0, (mx - mn) / np.where(mx > 0, mx, 1), 0.0)
    sec = np.minimum(11, (hue * 12).astype(np.int64))
    return np.where((s >= 0.15) & (mx >= 0.1), sec, -1)


def main():
    mat, sol = read_rgb(sys.argv[1]), read_rgb(sys.argv[2])
    h, w = mat.shape[:2]
    cx, cy = int(float(sys.argv[3])), int(float(sys.argv[4]))
    box = (slice(max(0, cy - 150), min(h, cy + 150)), slice(max(0, cx - 200), min(w, cx + 200)))
    m, s = mat[box].reshape(-1, 3), sol[box].reshape(-1, 3)
    changed = np.abs(m - s).sum(axis=1) > 60
    m, s = m[changed], s[changed]
    sol_sec, mat_sec = sectors(s), sectors(m)
    sol_bins = np.bincount(sol_sec[sol_sec >= 0], minlength=12)
    mat_bins = np.bincount(mat_sec[mat_sec >= 0], minlength=12)
    dom = int(np.argmax(sol_bins))
    n = max(1, len(m))
    print(len(m), 100 * int(sol_bins[dom]) // n, 100 * int(mat_bins[dom]) // n)


if __name__ == "__main__":
    main()
