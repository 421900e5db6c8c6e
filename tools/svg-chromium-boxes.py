#!/usr/bin/env python3
"""Chromium's rendering of each SVG in a folder, as the box of its dark pixels: what SvgReader must agree with.

    tools/svg-chromium-boxes.py assets/drawings/symbols > assets/drawings/symbols/chromium-boxes.json

Each SVG is a 200 x 200 px page (viewBox 0 0 200 200) of black shapes; chromium --headless --screenshot renders it and
the box [left, top, right, bottom] in px of the pixels darker than mid-grey is printed (right and bottom exclusive), so
tests compare the planned drawing's bounds with what a browser draws (issue 32, finding 9). Standard library only.
"""
import json
import os
import struct
import subprocess
import sys
import tempfile
import zlib


def read_png(path):
    """Width, height and rows of (r, g, b) for an 8-bit RGB or RGBA, non-interlaced PNG (what Chromium writes)."""
    with open(path, "rb") as f:
        data = f.read()
    if data[:8] != b"\x89PNG\r\n\x1a\n":
        raise ValueError(f"{path}: not a PNG")
    pos, idat, width, height, colour = 8, b"", 0, 0, 0
    while pos < len(data):
        length, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + length]
        if kind == b"IHDR":
            width, height, depth, colour, _, _, interlace = struct.unpack(">IIBBBBB", body)
            if depth != 8 or colour not in (2, 6) or interlace:
                raise ValueError(f"{path}: PNG of depth {depth}, colour type {colour}, interlace {interlace}")
        elif kind == b"IDAT":
            idat += body
        pos += 12 + length
    channels = 3 if colour == 2 else 4
    raw = zlib.decompress(idat)
    stride = width * channels
    rows, previous = [], bytearray(stride)
    for y in range(height):
        kind = raw[y * (stride + 1)]
        line = bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        for i in range(stride):
            a = line[i - channels] if i >= channels else 0
            b = previous[i]
            c = previous[i - channels] if i >= channels else 0
            if kind == 1:
                line[i] = (line[i] + a) & 0xFF
            elif kind == 2:
                line[i] = (line[i] + b) & 0xFF
            elif kind == 3:
                line[i] = (line[i] + (a + b) // 2) & 0xFF
            elif kind == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                line[i] = (line[i] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 0xFF
        rows.append([tuple(line[x * channels:x * channels + 3]) for x in range(width)])
        previous = line
    return width, height, rows


def dark_box(rows):
    xs, ys = [], []
    for y, row in enumerate(rows):
        for x, (r, g, b) in enumerate(row):
            if r + g + b < 3 * 128:
                xs.append(x)
                ys.append(y)
    return [min(xs), min(ys), max(xs) + 1, max(ys) + 1] if xs else None


def render(svg, png):
    chromium = os.environ.get("CHROMIUM", "chromium")
    subprocess.run([chromium, "--headless", "--no-sandbox", "--disable-gpu", "--hide-scrollbars", "--force-device-scale-factor=1",
                    "--default-background-color=ffffffff", "--window-size=200,200", f"--screenshot={png}", "file://" + os.path.abspath(svg)],
                   check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)


def main():
    folder = sys.argv[1] if len(sys.argv) > 1 else "assets/drawings/symbols"
    boxes = {}
    with tempfile.TemporaryDirectory() as temp:
        for name in sorted(os.listdir(folder)):
            if name.endswith(".svg"):
                png = os.path.join(temp, name + ".png")
                render(os.path.join(folder, name), png)
                boxes[name] = dark_box(read_png(png)[2])
    json.dump(boxes, sys.stdout, indent=1)
    print()


if __name__ == "__main__":
    main()
