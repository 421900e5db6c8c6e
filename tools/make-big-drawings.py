#!/usr/bin/env python3
"""Writes the drawing-budget benchmark's files: two large real drawings that must plan within seconds, and the hostile
ones that must be refused fast, naming the limit and the file (docs/vectors.md, "Limits").

    tools/make-big-drawings.py OUT_FOLDER

Real:    lines-300k.dxf (300 000 LINEs, a hatch of short strokes), polyline-500k.svg (one polyline of 500 000 points),
         zigzag-500k.svg (one polyline of 500 000 points turning 90 degrees at every one: 499 999 strokes).
Hostile: insert-array.dxf (an INSERT with a 32767 x 32767 array), nested-blocks.dxf (blocks 11 deep, 6 INSERTs each),
         use-4-15.svg (<use> expanded 4^15 times), nested-g.svg (200 000 nested <g>), subpaths-1m.svg (1 000 000
         subpaths), layers-20k.json (a job file of 20 000 layers).
Time each with: /usr/bin/time -v laserengrave plan FILE --width-mm 50 --origin-mm 5,5   (job: plan --job FILE);
the issue-38 targets: zigzag-500k.svg at --width-mm 50 and lines-300k.dxf at --width-mm 10, each <= 5 s and <= 300 MB.
"""
import math
import os
import sys


def dxf(entities: str, blocks: str = "") -> str:
    head = "0\nSECTION\n2\nHEADER\n9\n$INSUNITS\n70\n4\n0\nENDSEC\n"
    blk = f"0\nSECTION\n2\nBLOCKS\n{blocks}0\nENDSEC\n" if blocks else ""
    return f"{head}{blk}0\nSECTION\n2\nENTITIES\n{entities}0\nENDSEC\n0\nEOF\n"


def line(x0, y0, x1, y1, layer="0") -> str:
    return f"0\nLINE\n8\n{layer}\n10\n{x0:.4f}\n20\n{y0:.4f}\n11\n{x1:.4f}\n21\n{y1:.4f}\n"


def insert(block, x=0.0, y=0.0, columns=1, rows=1, spacing=1.0) -> str:
    return f"0\nINSERT\n8\n0\n2\n{block}\n10\n{x}\n20\n{y}\n70\n{columns}\n71\n{rows}\n44\n{spacing}\n45\n{spacing}\n"


def block(name, body) -> str:
    return f"0\nBLOCK\n8\n0\n2\n{name}\n70\n0\n10\n0\n20\n0\n{body}0\nENDBLK\n"


def svg(body: str) -> str:
    return f'<svg xmlns="http://www.w3.org/2000/svg" xmlns:xlink="http://www.w3.org/1999/xlink" width="100mm" height="100mm" viewBox="0 0 100 100">\n{body}\n</svg>\n'


def main() -> None:
    out = sys.argv[1]
    os.makedirs(out, exist_ok=True)

    def write(name, text):
        with open(os.path.join(out, name), "w") as f:
            f.write(text)

    # 300 000 short strokes on a 600 x 500 grid of 0.15 mm cells, each at its own angle: a hatch as CAM programs export it.
    strokes = []
    for i in range(300_000):
        cx, cy = (i % 600) * 0.15, (i // 600) * 0.15
        a = (i * 0.61803) % math.pi
        strokes.append(line(cx, cy, cx + 0.1 * math.cos(a), cy + 0.1 * math.sin(a)))
    write("lines-300k.dxf", dxf("".join(strokes)))

    # One polyline of 500 000 points: a spiral of 50 turns.
    points = []
    for i in range(500_000):
        t = i / 500_000
        r = 2 + 45 * t
        a = t * 50 * 2 * math.pi
        points.append(f"{50 + r * math.cos(a):.4f},{50 + r * math.sin(a):.4f}")
    write("polyline-500k.svg", svg(f'<polyline fill="none" stroke="black" points="{" ".join(points)}"/>'))

    # One polyline of 500 000 points zigzagging in 500 rows of 1000 (serpentine): every vertex a right angle the axes
    # cannot follow, so every segment is a stroke of its own (at 50 mm wide: 71 um strokes, 9.8 h of burning).
    zigzag = []
    for i in range(500_000):
        row, col = divmod(i, 1000)
        x = col if row % 2 == 0 else 999 - col
        zigzag.append(f"{x * 0.1:.1f},{row * 0.2 + (col % 2) * 0.1:.1f}")
    write("zigzag-500k.svg", svg(f'<polyline fill="none" stroke="black" points="{" ".join(zigzag)}"/>'))

    write("insert-array.dxf", dxf(insert("B", columns=32767, rows=32767, spacing=0.01), block("B", line(0, 0, 0.005, 0.005))))

    blocks = [block("B0", line(0, 0, 0.001, 0.001))]
    for level in range(1, 12):
        blocks.append(block(f"B{level}", "".join(insert(f"B{level - 1}", x=k * 0.01) for k in range(6))))
    write("nested-blocks.dxf", dxf(insert("B11"), "".join(blocks)))

    defs = ['<path id="u0" d="M0 0 L0.001 0.001"/>']
    for level in range(1, 16):
        defs.append(f'<g id="u{level}">' + "".join(f'<use xlink:href="#u{level - 1}" x="{k * 0.001}"/>' for k in range(4)) + "</g>")
    write("use-4-15.svg", svg("<defs>" + "".join(defs) + '</defs><use xlink:href="#u15"/>'))

    write("nested-g.svg", svg("<g>" * 200_000 + '<path d="M0 0 L1 1"/>' + "</g>" * 200_000))

    write("subpaths-1m.svg", svg('<path d="' + " ".join(f"M{(i % 1000) * 0.1:.1f} {(i // 1000) * 0.1:.1f} l0.05 0.05" for i in range(1_000_000)) + '"/>'))

    qr = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", "assets", "qr-code.bmp"))
    write("layers-20k.json", '{"layers":[' + ",".join(f'{{"source":"{qr}","widthMm":1}}' for _ in range(20_000)) + "]}")


if __name__ == "__main__":
    main()
