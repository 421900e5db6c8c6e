#!/usr/bin/env python3
"""The firmware's side of the differential test: one recorded gate stream through the AVR image in simavr.

    differential.py GATE_SIM GATE.elf STREAM.txt RESULT.txt [--check]

For every frequency line of the stream (FREQ, OFF, BURST) writes "INDEX LINE PULSES FIRST_CYCLE" (INDEX counts the
stream's lines from 0; FIRST_CYCLE is the first pulse's rising edge, or - without one): the pulses of the trains that
line started (see below). With --check, compares with RESULT.txt instead and fails
when the image no longer does what the committed result says (tests/LaserEngrave.Simulator.Tests reads that file and
holds the twin to it: GateFirmwareDifferentialTests)."""
import os
import subprocess
import sys
import tempfile

from bursts import group

gate_sim, elf, stream, result = sys.argv[1:5]
check = "--check" in sys.argv[5:]

lines = []
with open(stream) as f:
    for row in f:
        if row.startswith("#") or not row.strip():
            continue
        at, text = row.rstrip("\n").split(" ", 1)
        lines.append((int(at), text))
end = lines[-1][0] + 16_000_000 * 2
fd, script = tempfile.mkstemp(suffix=".txt")
with os.fdopen(fd, "w") as f:
    f.writelines(f"{at} {text}\n" for at, text in lines)
    f.write(f"end {end}\n")
out = subprocess.run([gate_sim, elf, script], capture_output=True, text=True, check=True).stdout
os.remove(script)
rises, level = [], 0
for row in out.splitlines():
    parts = row.split(" ")
    if parts[0] == "edge":
        v = int(parts[2])
        if v and not level:
            rises.append(int(parts[1]))
        level = v

freq, counts = group(lines, rises)
rows = [f"{i} {text.replace(' ', '_')} {counts[i][0]} {counts[i][1] if counts[i][1] is not None else '-'}"
        for i, _, text in freq]
text = "# index line pulses first-pulse-cycle (16 MHz), from " + stream.split("/")[-1] + " through the AVR image in simavr\n" + "\n".join(rows) + "\n"
if check:
    with open(result) as f:
        same = f.read() == text
    print(f"differential (simavr): {1 if same else 0} passed, {0 if same else 1} failed"
          + ("" if same else f": the AVR image no longer gives {result}; regenerate it (make -C firmware/gate differential)"))
    sys.exit(0 if same else 1)
with open(result, "w") as f:
    f.write(text)
print(f"{len(rows)} frequency lines, {sum(int(x.split()[2]) for x in rows)} pulses")
