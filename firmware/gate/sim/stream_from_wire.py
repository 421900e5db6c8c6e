#!/usr/bin/env python3
"""A recorded gate stream from a wire recording (the flight recorder's format; `--sim-wire FILE` on a twin run).

    stream_from_wire.py WIRE.jsonl STREAM.txt [FROM_S TO_S]

Writes one gate line a row, "CYCLE TEXT" (gate_sim's script format): the cycle at 16 MHz at which the line's last byte
has arrived at the gate. Each host write reaches the wire 1 ms after it was written (the twin's mean adapter latency)
and takes 10 bits a byte at 9600 baud behind whatever is still on the wire. simavr's UART takes 11 bits a byte
(gate_sim.c), so a line that would overlap the one before it on simavr's slower wire is moved later, and the stream
then holds the moved time: both the firmware and the twin are fed exactly these times."""
import json
import sys

F = 16_000_000
SIM_BYTE = 1664 * 11
wire, out = sys.argv[1], sys.argv[2]
t_from = float(sys.argv[3]) if len(sys.argv) > 3 else 0.0
t_to = float(sys.argv[4]) if len(sys.argv) > 4 else 1e9

rows, free, last = [], 0.0, None
with open(wire) as f:
    for row in f:
        e = json.loads(row)
        if e.get("p") != "l" or e.get("d") != "w":
            continue
        data = bytes.fromhex(e["x"])
        start = max(e["t"] + 0.001, free)
        free = start + len(data) * 10 / 9600
        if not (t_from <= e["t"] < t_to):
            continue
        text_end = free
        # A write may hold more than one line: each ends at its own '\n'.
        offset = 0
        for line in data.split(b"\n")[:-1]:
            offset += len(line) + 1
            at = start + offset * 10 / 9600
            cycle = round((at - t_from + 0.1) * F)
            if last is not None and cycle - last < (len(line) + 1) * SIM_BYTE:
                cycle = last + (len(line) + 1) * SIM_BYTE
            rows.append(f"{cycle} {line.decode('ascii')}")
            last = cycle
with open(out, "w") as f:
    f.write(f"# gate lines from {wire.split('/')[-1]}, host writes from {t_from} s to {min(t_to, 1e9)} s; "
            "cycle = the line's last byte at the gate, 16 MHz, from 0.1 s before the first\n")
    f.write("\n".join(rows) + "\n")
print(f"{len(rows)} lines")
