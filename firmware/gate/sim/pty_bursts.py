#!/usr/bin/env python3
"""A wall-clock run of the gate image (gate_pty) cut into the differential test's two files (docs/gate-firmware.md):

    pty_bursts.py LINES.txt EDGES.txt FIRST_LINE STREAM_OUT BURSTS_OUT [TITLE]

LINES.txt and EDGES.txt are what gate_pty recorded ("CYCLE TEXT" a received line, "CYCLE 0|1" a pulse-pin edge).
From line FIRST_LINE on (0-based; the engrave's first line in sim/host-bench.sh), writes the stream as the twin and
sim/gate_sim.c take it (cycles from 0.1 s before that line) and, for every FREQ, OFF and BURST line, the pulses the
image fired for it and its first pulse's cycle, grouped exactly as sim/differential.py groups gate_sim's pulses, so
that `differential.py ... STREAM_OUT BURSTS_OUT --check` proves the wall-clock run and the cycle-exact replay agree."""
import sys

from bursts import group

lines_path, edges_path, first, stream_out, bursts_out = sys.argv[1:6]
title = sys.argv[6] if len(sys.argv) > 6 else "gate lines recorded by gate_pty"
rows = []
for row in open(lines_path):
    at, _, text = row.rstrip("\n").partition(" ")
    rows.append((int(at), text))
rows = rows[int(first):]
origin = rows[0][0] - 1_600_000
lines = [(at - origin, text) for at, text in rows]
rises, level = [], 0
for row in open(edges_path):
    parts = row.split()
    if len(parts) != 2:
        continue
    c, v = int(parts[0]) - origin, int(parts[1])
    if v and not level and c > 0:
        rises.append(c)
    level = v


freq, counts = group(lines, rises)
with open(stream_out, "w") as f:
    f.write(f"# {title}; cycle = the line's last byte at the gate (RXC), 16 MHz, from 0.1 s before its first line\n")
    f.writelines(f"{at} {text}\n" for at, text in lines)
with open(bursts_out, "w") as f:
    f.write("# index line pulses first-pulse-cycle (16 MHz), from " + stream_out.split("/")[-1] + " through the AVR image in simavr\n")
    f.writelines(f"{i} {text.replace(' ', '_')} {counts[i][0]} {counts[i][1] if counts[i][1] is not None else '-'}\n" for i, _, text in freq)
print(f"{len(lines)} lines, {sum(1 for i, _, _ in freq if counts[i][1] is not None)} trains, {sum(c[0] for c in counts.values())} pulses")
