#!/usr/bin/env python3
"""Writes assets/drawings/layers.svg: a plate with two Inkscape layers, "mark" (an alignment cross and a ring) and "cut"
(the rounded outline and two holes), for the job of layers in assets/jobs/plate.json (docs/vectors.md, "Layers").
Plain text, no libraries: run it from the repository's root."""
import os

OUT = os.path.join("assets", "drawings", "layers.svg")

SVG = """<?xml version="1.0" encoding="UTF-8"?>
<svg xmlns="http://www.w3.org/2000/svg" xmlns:inkscape="http://www.inkscape.org/namespaces/inkscape"
     width="30mm" height="20mm" viewBox="0 0 30 20">
  <g inkscape:groupmode="layer" inkscape:label="mark" id="layer-mark">
    <line id="cross-h" x1="3" y1="5" x2="7" y2="5"/>
    <line id="cross-v" x1="5" y1="3" x2="5" y2="7"/>
    <circle id="ring" cx="25" cy="5" r="1"/>
  </g>
  <g inkscape:groupmode="layer" inkscape:label="cut" id="layer-cut">
    <rect id="outline" x="0" y="0" width="30" height="20" rx="2" ry="2"/>
    <circle id="hole-left" cx="10" cy="12" r="2"/>
    <circle id="hole-right" cx="20" cy="12" r="2"/>
  </g>
</svg>
"""

if __name__ == "__main__":
    with open(OUT, "w") as f:
        f.write(SVG)
    print(OUT)
