#!/usr/bin/python3
"""Makes the test drawings in assets/drawings/ and their exact figures in assets/drawings/expected.json.

DXF files are written with ezdxf (Debian: apt-get install python3-ezdxf); the SVGs are written as text, and
text-as-paths.svg is text.svg with its text converted to paths by Inkscape (apt-get install inkscape). Every shape's
exact length is computed here from the shape's own definition (closed forms for lines and circles, a polyline of
200,000 points per curve for ellipses, Beziers and splines, through ezdxf's own B-spline evaluator), so the tests
compare LaserEngrave's readers against figures that do not come from LaserEngrave.

Run from the repository root:  /usr/bin/python3 tools/make-test-drawings.py
"""
import json
import math
import os
import random
import shutil
import subprocess

import ezdxf
import numpy as np
from ezdxf.math import BSpline

OUT = os.path.join(os.path.dirname(__file__), "..", "assets", "drawings")
N = 200_000
expected = {}


def polyline_length(points):
    p = np.asarray(points, dtype=float)
    return float(np.sum(np.hypot(np.diff(p[:, 0]), np.diff(p[:, 1]))))



class Figures:
    """Exact length, the curved part's sum of length / radius (for the s / (3 r) allowance), and the polyline vertices."""

    def __init__(self):
        self.length = 0.0
        self.length_over_radius = 0.0
        self.vertices = []
        self.paths = 0

    def line(self, a, b):
        self.length += math.dist(a, b)

    def circle_arc(self, r, sweep_degrees):
        arc = r * math.radians(abs(sweep_degrees))
        self.length += arc
        self.length_over_radius += arc / r

    def curve(self, xs, ys):
        self.length += polyline_length(np.stack([xs, ys], axis=1))

    def polygon(self, pts, closed=True):
        ring = list(pts) + ([pts[0]] if closed else [])
        for a, b in zip(ring, ring[1:]):
            self.line(a, b)
        self.vertices.extend([list(p) for p in pts])

    def save(self, name, bounds, **extra):
        expected[name] = {
            "lengthMm": self.length,
            "lengthOverRadius": self.length_over_radius,
            "vertices": self.vertices,
            "bounds": bounds,
            "paths": self.paths,
            **extra,
        }


def hexagon(cx, cy, r, phase=0.0):
    return [(cx + r * math.cos(phase + k * math.pi / 3), cy + r * math.sin(phase + k * math.pi / 3)) for k in range(6)]


def new_doc(version="R2010"):
    doc = ezdxf.new(version)
    doc.header["$INSUNITS"] = 4  # millimetres
    return doc


def hexagons():
    """Three hexagons (circumradius 10 mm), each with a round hole and a hexagonal hole drawn as six LINEs; outlines first."""
    doc = new_doc()
    msp = doc.modelspace()
    fig = Figures()
    centres = [(12.0, 10.0), (34.5, 10.0), (23.25, 29.485571585149868)]
    for cx, cy in centres:
        pts = hexagon(cx, cy, 10.0, math.pi / 6)
        msp.add_lwpolyline(pts, close=True)
        fig.polygon(pts)
        fig.paths += 1
    for cx, cy in centres:
        msp.add_circle((cx - 3.2, cy), 3.5)
        fig.circle_arc(3.5, 360)
        small = hexagon(cx + 4.0, cy, 2.0)
        for a, b in zip(small, small[1:] + small[:1]):
            msp.add_line(a, b)
            fig.line(a, b)
        fig.vertices.extend([list(p) for p in small])
        fig.paths += 2
    xs = [p[0] for c in centres for p in hexagon(*c, 10.0, math.pi / 6)]
    ys = [p[1] for c in centres for p in hexagon(*c, 10.0, math.pi / 6)]
    doc.saveas(os.path.join(OUT, "hexagons.dxf"))
    fig.save("hexagons.dxf", [min(xs), min(ys), max(xs), max(ys)], yUp=True)


def scattered():
    """60 small shapes (squares, triangles, open zig-zags, circles) scattered over 50 x 40 mm, in random order."""
    doc = new_doc()
    msp = doc.modelspace()
    fig = Figures()
    rng = random.Random(14)
    for i in range(60):
        x, y = rng.uniform(0, 48), rng.uniform(0, 38)
        kind = i % 4
        if kind == 0:
            pts = [(x, y), (x + 2, y), (x + 2, y + 2), (x, y + 2)]
            msp.add_lwpolyline(pts, close=True)
            fig.polygon(pts)
        elif kind == 1:
            pts = [(x, y), (x + 2, y), (x + 1, y + 1.7)]
            msp.add_lwpolyline(pts, close=True)
            fig.polygon(pts)
        elif kind == 2:
            pts = [(x, y), (x + 0.5, y + 1.5), (x + 1, y), (x + 1.5, y + 1.5)]
            msp.add_lwpolyline(pts)
            fig.polygon(pts, closed=False)
        else:
            msp.add_circle((x + 1, y + 1), 1.0)
            fig.circle_arc(1.0, 360)
        fig.paths += 1
    doc.saveas(os.path.join(OUT, "scattered.dxf"))
    fig.save("scattered.dxf", None, yUp=True)


def curves(version):
    """Every curve entity: ARC, CIRCLE, bulged LWPOLYLINE / POLYLINE, and for R2000+ ELLIPSE and SPLINE."""
    doc = new_doc(version)
    msp = doc.modelspace()
    fig = Figures()
    msp.add_arc((10, 10), 8, 30, 250)
    fig.circle_arc(8, 220)
    msp.add_circle((35, 10), 6)
    fig.circle_arc(6, 360)
    fig.paths += 2

    # A slot: two lines and two half circles of radius 4 (bulge 1 = a half circle, counter-clockwise).
    slot = [(50, 4, 0), (70, 4, 1), (70, 12, 0), (50, 12, 1)]
    if version == "R12":
        msp.add_polyline2d([(x, y, 0, 0, b) for x, y, b in slot], format="xyseb", close=True)
    else:
        msp.add_lwpolyline(slot, format="xyb", close=True)
    fig.line((50, 4), (70, 4))
    fig.line((70, 12), (50, 12))
    fig.circle_arc(4, 180)
    fig.circle_arc(4, 180)
    fig.vertices.extend([[50, 4], [70, 4], [70, 12], [50, 12]])
    fig.paths += 1

    # An open polyline with a quarter-circle bulge (tan(90°/4)) and a clockwise 120° bulge.
    b1, b2 = math.tan(math.radians(90) / 4), -math.tan(math.radians(120) / 4)
    p0, p1, p2, p3 = (5, 30), (15, 30), (25, 40), (35, 40)
    pts = [(*p0, 0), (*p1, b1), (*p2, b2), p3 + (0,)]
    if version == "R12":
        msp.add_polyline2d([(x, y, 0, 0, b) for x, y, b in pts], format="xyseb")
    else:
        msp.add_lwpolyline(pts, format="xyb")
    fig.line(p0, p1)
    r1 = math.dist(p1, p2) / (2 * math.sin(math.radians(90) / 2))
    fig.circle_arc(r1, 90)
    r2 = math.dist(p2, p3) / (2 * math.sin(math.radians(120) / 2))
    fig.circle_arc(r2, 120)
    fig.vertices.extend([list(p0), list(p1), list(p2), list(p3)])
    fig.paths += 1

    if version != "R12":
        # A full ellipse (axes 10 and 6.5, tilted 30°) and a part of one.
        c, major, ratio = np.array([60.0, 32.0]), np.array([10 * math.cos(math.radians(30)), 10 * math.sin(math.radians(30))]), 0.65
        msp.add_ellipse((*c, 0), (*major, 0), ratio, 0, 2 * math.pi)
        minor = ratio * np.array([-major[1], major[0]])
        t = np.linspace(0, 2 * math.pi, N + 1)
        pts_e = c[None, :] + np.outer(np.cos(t), major) + np.outer(np.sin(t), minor)
        fig.curve(pts_e[:, 0], pts_e[:, 1])
        msp.add_ellipse((85, 32, 0), (0, 9, 0), 0.5, 0.5, 4.0)
        t = np.linspace(0.5, 4.0, N + 1)
        maj2, min2 = np.array([0.0, 9.0]), 0.5 * np.array([-9.0, 0.0])
        pts_e = np.array([85.0, 32.0])[None, :] + np.outer(np.cos(t), maj2) + np.outer(np.sin(t), min2)
        fig.curve(pts_e[:, 0], pts_e[:, 1])

        # A gentle open cubic spline and a rational (weighted) quadratic one.
        ctrl = [(5, 55), (20, 70), (40, 50), (60, 70), (80, 55)]
        msp.add_open_spline(ctrl, degree=3)
        sp = np.array([tuple(v)[:2] for v in BSpline(ctrl, order=4).approximate(N)])
        fig.curve(sp[:, 0], sp[:, 1])
        ctrl2 = [(10, 80), (30, 95), (50, 80), (70, 95), (90, 80)]
        weights = [1, 2, 0.7, 1.5, 1]
        spline = msp.add_open_spline(ctrl2, degree=2)
        spline.weights = weights
        rs = BSpline(ctrl2, order=3, weights=weights)
        sp = np.array([tuple(v)[:2] for v in rs.approximate(N)])
        fig.curve(sp[:, 0], sp[:, 1])
        fig.paths += 4
    name = "curves-r12.dxf" if version == "R12" else "curves.dxf"
    doc.saveas(os.path.join(OUT, name))
    fig.save(name, None, yUp=True)


def blocks():
    """Blocks inserted scaled, rotated, mirrored, nested and arrayed (MINSERT); plus text, a hatch and a frozen layer to warn about."""
    doc = new_doc()
    msp = doc.modelspace()
    fig = Figures()
    bolt = doc.blocks.new(name="BOLT", base_point=(1, 1))
    bolt.add_circle((1, 1), 1.0)
    bolt.add_line((0, 1), (2, 1))
    plate = doc.blocks.new(name="PLATE")
    plate.add_lwpolyline([(0, 0), (12, 0), (12, 8), (0, 8)], close=True)
    plate.add_blockref("BOLT", (3, 4))
    plate.add_blockref("BOLT", (9, 4), dxfattribs={"xscale": 1.5, "yscale": 1.5, "rotation": 90})

    def plate_length(s):
        return s * (40 + (2 * math.pi + 2) + 1.5 * (2 * math.pi + 2))

    def plate_over_radius(s):
        return 2 * math.pi + 2 * math.pi

    inserts = [((5, 5), 1, 0), ((25, 5), 1.25, 30), ((45, 8), 0.8, -90)]
    for at, s, rot in inserts:
        msp.add_blockref("PLATE", at, dxfattribs={"xscale": s, "yscale": s, "rotation": rot})
        fig.length += plate_length(s)
        fig.length_over_radius += plate_over_radius(s)
    # Mirrored: x scale -1.
    msp.add_blockref("PLATE", (80, 30), dxfattribs={"xscale": -1, "yscale": 1})
    fig.length += plate_length(1)
    fig.length_over_radius += plate_over_radius(1)
    # A 3 x 2 array of bolts.
    msp.add_blockref("BOLT", (5, 40), dxfattribs={"column_count": 3, "row_count": 2, "column_spacing": 4, "row_spacing": 5})
    fig.length += 6 * (2 * math.pi + 2)
    fig.length_over_radius += 6 * 2 * math.pi
    fig.paths = 4 * 5 + 12
    msp.add_text("PLATES", dxfattribs={"height": 2}).set_placement((5, 55))
    msp.add_text("x", dxfattribs={"height": 2}).set_placement((15, 55))
    hatch = msp.add_hatch()
    hatch.paths.add_polyline_path([(60, 50), (70, 50), (70, 55)], is_closed=True)
    doc.layers.add("HIDDEN")
    doc.layers.get("HIDDEN").freeze()
    msp.add_line((0, 60), (10, 60), dxfattribs={"layer": "HIDDEN"})
    doc.saveas(os.path.join(OUT, "blocks.dxf"))
    fig.save("blocks.dxf", None, yUp=True, warnings=["2 TEXT", "1 HATCH", "1 LINE"])


def svg():
    """Every path command (absolute, relative, implicit repeats, arcs), every shape, transforms, a viewBox in mm, hidden and text elements."""
    fig = Figures()
    mm = 0.5  # viewBox 240 x 160 on 120 x 80 mm
    els = []

    def matrix(a, b, c, d, e, f):
        return np.array([[a, c, e], [b, d, f], [0, 0, 1]], dtype=float)

    ident = matrix(1, 0, 0, 1, 0, 0)

    def add_curve(m, xs, ys):
        p = m @ np.vstack([xs, ys, np.ones_like(xs)])
        fig.curve(p[0] * mm, p[1] * mm)

    def add_line(m, a, b):
        add_curve(m, np.array([a[0], b[0]], float), np.array([a[1], b[1]], float))

    def cubic(m, p0, p1, p2, p3):
        t = np.linspace(0, 1, N + 1)[None, :]
        P = [np.array(p, float)[:, None] for p in (p0, p1, p2, p3)]
        c = (1 - t) ** 3 * P[0] + 3 * (1 - t) ** 2 * t * P[1] + 3 * (1 - t) * t ** 2 * P[2] + t ** 3 * P[3]
        add_curve(m, c[0], c[1])

    def quad(m, p0, p1, p2):
        t = np.linspace(0, 1, N + 1)[None, :]
        P = [np.array(p, float)[:, None] for p in (p0, p1, p2)]
        c = (1 - t) ** 2 * P[0] + 2 * (1 - t) * t * P[1] + t ** 2 * P[2]
        add_curve(m, c[0], c[1])

    def ellipse_arc(m, c, rx, ry, phi_deg, t0, t1):
        t = np.linspace(t0, t1, N + 1)
        phi = math.radians(phi_deg)
        x = c[0] + rx * np.cos(t) * math.cos(phi) - ry * np.sin(t) * math.sin(phi)
        y = c[1] + rx * np.cos(t) * math.sin(phi) + ry * np.sin(t) * math.cos(phi)
        add_curve(m, x, y)

    def poly(m, pts, closed):
        ring = pts + ([pts[0]] if closed else [])
        for a, b in zip(ring, ring[1:]):
            add_line(m, a, b)

    # 1. Lines: absolute and relative L, H, V, Z; a moveto with implicit lineto repeats, absolute and relative.
    els.append('<path id="lines" d="M10,10 L40,10 l0,20 H25 h-10 V15 v-5 z M50 10 60 10 60 20 m 10 -10 5 0 0 5"/>')
    poly(ident, [(10, 10), (40, 10), (40, 30), (25, 30), (15, 30), (15, 15), (15, 10)], True)
    poly(ident, [(50, 10), (60, 10), (60, 20)], False)
    poly(ident, [(70, 10), (75, 10), (75, 15)], False)

    # 2. Curves: C then S (reflected control), Q then T (reflected), absolute and relative.
    els.append('<path id="curves" d="M20 60 C30 40 50 40 60 60 S90 80 100 60 Q110 40 120 60 T140 60"/>')
    cubic(ident, (20, 60), (30, 40), (50, 40), (60, 60))
    cubic(ident, (60, 60), (70, 80), (90, 80), (100, 60))
    quad(ident, (100, 60), (110, 40), (120, 60))
    quad(ident, (120, 60), (130, 80), (140, 60))
    els.append('<path id="relative-curves" d="m20 100 c10-20 30-20 40 0 s30 20 40 0 q10-20 20 0 t20 0"/>')
    cubic(ident, (20, 100), (30, 80), (50, 80), (60, 100))
    cubic(ident, (60, 100), (70, 120), (90, 120), (100, 100))
    quad(ident, (100, 100), (110, 80), (120, 100))
    quad(ident, (120, 100), (130, 120), (140, 100))

    # 3. Arcs: a half circle (r 15), half of a tilted ellipse (20 x 10 at 30°) ended on its major axis, radii too
    # small (scaled up to a half circle of r 15), a large 270° arc of r 10, a zero radius (a line), then Z.
    c30, s30 = math.cos(math.radians(30)), math.sin(math.radians(30))
    e0 = (180.0, 20.0)
    e1 = (180 + 40 * c30, 20 + 40 * s30)
    e2 = (e1[0], e1[1] + 30)
    e3 = (e2[0] - 10, e2[1] + 10)
    e4 = (e3[0] - 10, e3[1])
    d = (f"M150 20 A15 15 0 0 1 180 20 a20 10 30 0 1 {e1[0] - e0[0]!r} {e1[1] - e0[1]!r} "
         f"A5 5 0 0 0 {e2[0]!r} {e2[1]!r} A10 10 0 1 1 {e3[0]!r} {e3[1]!r} A0 4 0 0 1 {e4[0]!r} {e4[1]!r} Z")
    els.append(f'<path id="arcs" d="{d}"/>')
    fig.length += 15 * math.pi * mm
    fig.length_over_radius += math.pi
    ellipse_arc(ident, (e0[0] + 20 * c30, e0[1] + 20 * s30), 20, 10, 30, math.pi, 2 * math.pi)
    fig.length += 15 * math.pi * mm
    fig.length_over_radius += math.pi
    fig.length += 10 * 1.5 * math.pi * mm
    fig.length_over_radius += 1.5 * math.pi
    add_line(ident, e3, e4)
    add_line(ident, e4, (150, 20))

    # 4. Shapes: rounded rects (circular and elliptical corners), circle, ellipse, line, polyline, polygon.
    els.append('<rect id="rounded" x="160" y="100" width="40" height="25" rx="8"/>')
    fig.length += (2 * (40 - 16) + 2 * (25 - 16)) * mm + 2 * math.pi * 8 * mm
    fig.length_over_radius += 2 * math.pi
    els.append('<rect id="elliptic-corners" x="205" y="95" width="30" height="40" rx="10" ry="14"/>')
    fig.length += (2 * (30 - 20) + 2 * (40 - 28)) * mm
    ellipse_arc(ident, (0, 0), 10, 14, 0, 0, 2 * math.pi)
    els.append('<rect id="plain" x="5" y="130" width="20" height="20"/>')
    poly(ident, [(5, 130), (25, 130), (25, 150), (5, 150)], True)
    els.append('<circle id="circle" cx="110" cy="135" r="12"/>')
    fig.length += 2 * math.pi * 12 * mm
    fig.length_over_radius += 2 * math.pi
    els.append('<line id="line" x1="30" y1="155" x2="90" y2="145"/>')
    add_line(ident, (30, 155), (90, 145))
    els.append('<polyline id="polyline" points="150,150 160,140 170,150 180,140"/>')
    poly(ident, [(150, 150), (160, 140), (170, 150), (180, 140)], False)
    els.append('<polygon id="polygon" points="190,150 200,140 210,150"/>')
    poly(ident, [(190, 150), (200, 140), (210, 150)], True)

    # 5. Transforms: rotate about a point, and a group of translate, scale and skewX around a matrix.
    rot = matrix(1, 0, 0, 1, 60, 135) @ matrix(math.cos(math.radians(20)), math.sin(math.radians(20)), -math.sin(math.radians(20)), math.cos(math.radians(20)), 0, 0) @ matrix(1, 0, 0, 1, -60, -135)
    els.append('<ellipse id="tilted" cx="60" cy="135" rx="20" ry="10" transform="rotate(20 60 135)"/>')
    ellipse_arc(rot, (60, 135), 20, 10, 0, 0, 2 * math.pi)
    g = matrix(1, 0, 0, 1, 110, 40) @ matrix(0.8, 0, 0, 0.8, 0, 0) @ matrix(1, 0, math.tan(math.radians(10)), 1, 0, 0)
    inner = matrix(1, 0.2, -0.1, 0.9, 5, -3)
    els.append('<g id="skewed" transform="translate(110,40) scale(0.8) skewX(10)">'
               '<polygon id="skewed-square" points="0,0 20,0 20,20 0,20"/>'
               '<circle id="skewed-circle" cx="40" cy="10" r="10" transform="matrix(1 0.2 -0.1 0.9 5 -3)"/></g>')
    poly(g, [(0, 0), (20, 0), (20, 20), (0, 20)], True)
    ellipse_arc(g @ inner, (40, 10), 10, 10, 0, 0, 2 * math.pi)

    # 6. Not engraved, with a warning: text, and a hidden layer.
    els.append('<text id="label" x="10" y="158" font-size="6">LaserEngrave</text>')
    els.append('<g id="hidden" style="display:none"><circle cx="10" cy="10" r="3"/></g>')
    fig.paths = 16
    body = "\n  ".join(els)
    text = ('<?xml version="1.0" encoding="UTF-8"?>\n'
            '<svg xmlns="http://www.w3.org/2000/svg" width="120mm" height="80mm" viewBox="0 0 240 160">\n'
            f"  {body}\n</svg>\n")
    with open(os.path.join(OUT, "every-command.svg"), "w") as f:
        f.write(text)
    fig.save("every-command.svg", None, yUp=False, warnings=["<text>", "<g>"])


def text():
    """Text as typed (only warned about) and the same converted to paths by Inkscape (engraved)."""
    source = os.path.join(OUT, "text.svg")
    with open(source, "w") as f:
        f.write('<?xml version="1.0" encoding="UTF-8"?>\n'
                '<svg xmlns="http://www.w3.org/2000/svg" width="40mm" height="10mm" viewBox="0 0 40 10">\n'
                '  <text id="mark" x="1" y="8" font-family="DejaVu Sans" font-size="8">LE-14</text>\n</svg>\n')
    if shutil.which("inkscape") is None:
        print("inkscape not found: text-as-paths.svg not remade")
        return
    subprocess.run(["inkscape", "--export-text-to-path", "--export-plain-svg",
                    "--export-filename=" + os.path.join(OUT, "text-as-paths.svg"), source],
                   check=True, stderr=subprocess.DEVNULL)


if __name__ == "__main__":
    os.makedirs(OUT, exist_ok=True)
    hexagons()
    scattered()
    curves("R2010")
    curves("R12")
    blocks()
    svg()
    text()
    with open(os.path.join(OUT, "expected.json"), "w") as f:
        json.dump(expected, f, indent=1)
        f.write("\n")
    print("wrote", ", ".join(sorted(expected)))
