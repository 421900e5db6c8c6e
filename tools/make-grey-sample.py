#!/usr/bin/env python3
"""Writes the grey sample, a photo-like 8-bit greyscale PNG to try dithering on: 320 x 240 px.

    tools/make-grey-sample.py OUT.png        (assets/grey-sample.png; the same bytes every time)

What it holds, so each dither can be judged by eye: a smooth left-to-right gradient behind everything (banding shows
at once), a face lit from the upper left (a shaded sphere with eyes, nose and mouth: soft tones and small dark
details, as a portrait), and along the bottom a step wedge of eleven greys from black to white (0, 10, ... 100 %).
Pure Python (zlib and struct only): no imaging package is needed.
"""
import math
import struct
import sys
import zlib

WIDTH, HEIGHT = 320, 240
WEDGE_TOP = 200


def shade(x: float, y: float) -> float:
    """Brightness 0 (black) .. 1 (white) at pixel centre (x, y)."""
    if y >= WEDGE_TOP:
        step = min(10, int(x * 11 / WIDTH))
        return step / 10
    value = 0.15 + 0.75 * x / (WIDTH - 1)  # the background gradient
    cx, cy, r = 160.0, 100.0, 80.0
    dx, dy = (x - cx) / r, (y - cy) / r
    d2 = dx * dx + dy * dy
    if d2 <= 1:
        # A sphere lit from the upper left: Lambert shading of its normal, never fully black.
        nz = math.sqrt(1 - d2)
        light = (-0.5, -0.6, 0.62)
        norm = math.sqrt(sum(c * c for c in light))
        lambert = max(0.0, (dx * light[0] + dy * light[1] + nz * light[2]) / norm)
        value = 0.2 + 0.75 * lambert
        for ex in (-0.35, 0.35):  # eyes: dark ovals with a bright catch-light
            ed = ((dx - ex) / 0.14) ** 2 + ((dy + 0.25) / 0.09) ** 2
            if ed <= 1:
                value = 0.08
                if ((dx - ex + 0.04) / 0.035) ** 2 + ((dy + 0.28) / 0.03) ** 2 <= 1:
                    value = 0.95
        if abs(dx) < 0.06 and -0.1 < dy < 0.2:  # the nose's shadow, a soft vertical stroke
            value *= 0.55 + 0.45 * abs(dx) / 0.06
        mouth = math.hypot(dx / 0.45, (dy - 0.2) / 0.3)  # a smile: the lower arc of an ellipse
        if 0.92 < mouth < 1.08 and dy > 0.35:
            value = 0.12
    return min(1.0, max(0.0, value))


def main() -> None:
    out = sys.argv[1]
    raw = bytearray()
    for y in range(HEIGHT):
        raw.append(0)  # filter: none
        raw += bytes(round(255 * shade(x + 0.5, y + 0.5)) for x in range(WIDTH))

    def chunk(kind: bytes, data: bytes) -> bytes:
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF)

    png = b"\x89PNG\r\n\x1a\n"
    png += chunk(b"IHDR", struct.pack(">IIBBBBB", WIDTH, HEIGHT, 8, 0, 0, 0, 0))  # 8-bit greyscale
    png += chunk(b"IDAT", zlib.compress(bytes(raw), 9))
    png += chunk(b"IEND", b"")
    with open(out, "wb") as f:
        f.write(png)


if __name__ == "__main__":
    main()
