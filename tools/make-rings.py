#!/usr/bin/env python3
"""Writes the planning benchmark's image of rings: a square 1-bit BMP of concentric black and white rings.

    tools/make-rings.py OUT.bmp [SIDE] [RING_PX]      (20000 px and 20 px by default)

Each ring is RING_PX wide, black and white in turn from the centre, out to the corners, so every row crosses many
runs of every length: `laserengrave plan OUT.bmp --width-mm 50 --origin-mm 5,5` has 13 M moves at the defaults
(docs/execution.md, "Planning speed"). The file is 50 MB at the default size: keep it out of git (write it to /tmp).
Rows are built from their run edges (a pixel is black when its centre lies in a black ring), so it takes a minute,
not hours, in plain Python.
"""
import math
import struct
import sys


def row_bits(y: int, side: int, ring: float) -> str:
    """The row as a string of '0' (black, palette index 0) and '1' (white), left to right."""
    c = side / 2
    dy = y + 0.5 - c
    edges = []  # pixel columns where the colour changes, ascending
    k_min = int(abs(dy) // ring)
    k_max = int(math.hypot(c, abs(dy)) // ring) + 1
    # Ring k spans radii [k ring, (k + 1) ring); black for even k. Pixel x is inside radius r when |x + 0.5 - c| < sqrt(r^2 - dy^2).
    half = []
    for k in range(k_min + 1, k_max + 1):
        r = k * ring
        if r * r > dy * dy:
            half.append(math.sqrt(r * r - dy * dy))
    # Colour at the centre column: ring index of |dy|.
    centre_black = k_min % 2 == 0
    # Boundaries to the right of centre: x + 0.5 - c >= h  <=>  x >= c + h - 0.5; the first column at or past it.
    right = [min(side, max(0, math.ceil(c + h - 0.5))) for h in half]
    left = [min(side, max(0, math.floor(c - h - 0.5) + 1)) for h in reversed(half)]
    edges = left + right
    out = []
    pos = 0
    # Colour left of the first edge: the outermost ring reached, alternating inwards.
    colour = centre_black if len(half) % 2 == 0 else not centre_black
    for e in edges:
        if e > pos:
            out.append(("0" if colour else "1") * (e - pos))
            pos = e
        colour = not colour
    if pos < side:
        out.append(("0" if colour else "1") * (side - pos))
    return "".join(out)


def main() -> None:
    out = sys.argv[1]
    side = int(sys.argv[2]) if len(sys.argv) > 2 else 20000
    ring = float(sys.argv[3]) if len(sys.argv) > 3 else 20
    stride = ((side + 31) // 32) * 4
    pad = stride * 8 - side
    palette = bytes([0, 0, 0, 0, 255, 255, 255, 0])
    offset = 14 + 40 + len(palette)
    size = stride * side
    with open(out, "wb") as f:
        f.write(b"BM" + struct.pack("<IHHI", offset + size, 0, 0, offset))
        f.write(struct.pack("<IiiHHIIiiII", 40, side, side, 1, 1, 0, size, 2835, 2835, 2, 2))
        f.write(palette)
        for y in range(side - 1, -1, -1):  # bottom-up rows
            bits = row_bits(y, side, ring) + "0" * pad
            f.write(int(bits, 2).to_bytes(stride, "big"))


if __name__ == "__main__":
    main()
