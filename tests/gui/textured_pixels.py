#!/usr/bin/env python3
"""textured_pixels.py MATERIAL.png SOLID.png CX CY

Compares a Material and a Solid screenshot of one view in the 400 × 300 px box around (CX, CY) (an object's centre
in pixels, from the GUI probe). Of the pixels that differ between the two (by more than 60 in R+G+B), Solid draws
most in one 30° hue sector: the object colour. Where Material draws the object's textures, almost none of those
pixels keep that hue. Prints "changed solid_share material_share" (the shares of Solid's dominant sector, in %).
Reads 8-bit RGB(A) PNGs (what the editor's F12 writes) with the standard library only; read_png is shared with
the other GUI tests that look at pixels (shading.sh).
"""
import colorsys
import struct
import sys
import zlib


def read_png(path):
    data = open(path, "rb").read()
    pos, idat = 8, b""
    while pos < len(data):
        n, t = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + n]
        if t == b"IHDR":
            w, h, depth, ctype = struct.unpack(">IIBB", body[:10])
            assert depth == 8 and ctype in (2, 6), "8-bit RGB(A) PNG expected"
            bpp = 4 if ctype == 6 else 3
        elif t == b"IDAT":
            idat += body
        pos += 12 + n
    raw, stride, prev, rows = zlib.decompress(idat), w * bpp, bytearray(w * bpp), []
    for y in range(h):
        f, line = raw[y * (stride + 1)], bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        for i in range(stride):
            a = line[i - bpp] if i >= bpp else 0
            b, c = prev[i], prev[i - bpp] if i >= bpp else 0
            if f == 1:
                line[i] = (line[i] + a) & 255
            elif f == 2:
                line[i] = (line[i] + b) & 255
            elif f == 3:
                line[i] = (line[i] + (a + b) // 2) & 255
            elif f == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                line[i] = (line[i] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        rows.append([tuple(line[x:x + 3]) for x in range(0, stride, bpp)])
        prev = line
    return w, h, rows


def sector(p):
    hue, s, v = colorsys.rgb_to_hsv(p[0] / 255, p[1] / 255, p[2] / 255)
    return min(11, int(hue * 12)) if s >= 0.15 and v >= 0.1 else -1


def main():
    (w, h, mat), (_, _, sol) = read_png(sys.argv[1]), read_png(sys.argv[2])
    cx, cy = int(float(sys.argv[3])), int(float(sys.argv[4]))
    pairs = [(mat[y][x], sol[y][x]) for y in range(max(0, cy - 150), min(h, cy + 150))
             for x in range(max(0, cx - 200), min(w, cx + 200))
             if sum(abs(mat[y][x][k] - sol[y][x][k]) for k in range(3)) > 60]
    sol_bins, mat_bins = [0] * 12, [0] * 12
    for m, s in pairs:
        if sector(s) >= 0:
            sol_bins[sector(s)] += 1
        if sector(m) >= 0:
            mat_bins[sector(m)] += 1
    dom = max(range(12), key=lambda k: sol_bins[k])
    n = max(1, len(pairs))
    print(len(pairs), 100 * sol_bins[dom] // n, 100 * mat_bins[dom] // n)


if __name__ == "__main__":
    main()
