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

def hz_of(text):
    words = text.split(" ")
    try:
        return int(words[2]) if words[0].upper() == "BURST" else int(words[1]) if words[0].upper() == "FREQ" else 0
    except (IndexError, ValueError):
        return 0


def fired_period(hz):
    """The firmware's grid (atmega328p/main.c, fired_period_cycles): cycles per period."""
    i = 0 if hz >= 245 else 1 if hz >= 31 else 2 if hz >= 4 else 3
    p = (1, 8, 64, 256)[i]
    return ((16_000_000 // p + hz // 2) // hz) * p


# A pulse belongs to the line whose command started its train: a train is a run of pulses one fired period apart, and
# the line that started it is the last frequency line to arrive before its first pulse (a line takes milliseconds to
# arrive, its first pulse comes within 0.21 ms). Pulses of a train still under way when the next line arrives (before
# that line has been processed) stay with the line that started the train.
freq = [(i, at, text) for i, (at, text) in enumerate(lines) if text.split(" ")[0].upper() in ("FREQ", "OFF", "BURST")]
counts = {i: [0, None] for i, _, _ in freq}
k, prev, period = -1, None, None
for r in rises:
    if prev is None or period is None or abs(r - prev - period) > 16:
        while k + 1 < len(freq) and freq[k + 1][1] < r:
            k += 1
        owner = freq[k][0]
        period = fired_period(hz_of(freq[k][2])) if hz_of(freq[k][2]) else None
        if counts[owner][1] is None:
            counts[owner][1] = r
    counts[owner][0] += 1
    prev = r
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
