#!/usr/bin/env python3
"""Writes the speed benchmark's random-noise image: a 1-bit BMP, 257 x 129 px, each pixel black with probability 0.5.

    tools/make-noise.py OUT.bmp [SEED]      (seed 42 by default; the same seed gives the same bytes)

docs/simulator.md times `engrave OUT.bmp --width-mm 10 --origin-mm 10,10 --simulate --json` on it.
"""
import random
import struct
import sys

WIDTH, HEIGHT = 257, 129


def main() -> None:
    out = sys.argv[1]
    rnd = random.Random(int(sys.argv[2]) if len(sys.argv) > 2 else 42)
    black = [[rnd.random() < 0.5 for _ in range(WIDTH)] for _ in range(HEIGHT)]
    stride = ((WIDTH + 31) // 32) * 4
    pixels = bytearray()
    for y in range(HEIGHT - 1, -1, -1):  # bottom-up rows
        row = bytearray(stride)
        for x in range(WIDTH):
            if not black[y][x]:  # palette index 1 = white
                row[x // 8] |= 0x80 >> (x % 8)
        pixels += row
    palette = bytes([0, 0, 0, 0, 255, 255, 255, 0])
    offset = 14 + 40 + len(palette)
    header = b"BM" + struct.pack("<IHHI", offset + len(pixels), 0, 0, offset)
    info = struct.pack("<IiiHHIIiiII", 40, WIDTH, HEIGHT, 1, 1, 0, len(pixels), 2835, 2835, 2, 2)
    with open(out, "wb") as f:
        f.write(header + info + palette + pixels)


if __name__ == "__main__":
    main()
