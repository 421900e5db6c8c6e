#!/usr/bin/env python3
"""The PIC16F628A image in gpsim against the protocol's vectors (make -C firmware/gate test-pic).

    pic_vectors.py GATE.cod WORKDIR

The host's lines go in as a bit-level stimulus on RB1/RX at 9600 baud (gpsim's USART receives them as a PIC would);
every write to TXREG (the replies), CCP1CON, PR2 and T2CON is logged by gpsim with its instruction cycle (1 us at
4 MHz), and every edge of the RB3 pin (the pulse train) is recorded by gpsim's FileRecorder module on the node that also
carries the jumper to RA4/T0CKI, which the firmware's burst counter counts. Pulses are counted and timed from those
edges. Prints one line per failed check, the figures, and "pic (gpsim): N passed, N failed"."""
import os
import re
import subprocess
import sys

cod, work = os.path.abspath(sys.argv[1]), os.path.abspath(sys.argv[2])
BIT = 1e6 / 9600
passed = failed = 0


def check(ok, name, detail=""):
    global passed, failed
    if ok:
        passed += 1
    else:
        failed += 1
        print(f"FAIL {name}: {detail}")


def run(lines, end, jumper=True):
    """lines: [(cycle the line's last stop bit ends, text)] -> (replies [(cycle, text)], writes [(cycle, reg, value)],
    edges [(cycle, level)] of RB3). jumper: RB3 wired to RB6/T1CKI, as the gate is built (docs/gate-firmware.md)."""
    changes, level = [], 1
    for at, text in lines:
        data = text.encode("latin-1") + b"\n"
        t = at - len(data) * 10 * BIT
        for b in data:
            for i, v in enumerate([0] + [(b >> k) & 1 for k in range(8)] + [1]):
                if v != level:
                    changes.append((round(t + i * BIT), v))
                    level = v
            t += 10 * BIT
    stimulus = ", ".join(f"{c}, {v}" for c, v in changes)
    script = f"{work}/vectors.stc"
    log = f"{work}/vectors.log"
    # gpsim runs in the script's folder; it drops a recorder file name longer than about 20 characters, so the names
    # are short and relative. Naming another file at the end closes (flushes) the first.
    edges_file = f"{work}/rb3.txt"
    jumper = " porta4" if jumper else ""
    with open(script, "w") as f:
        f.write(f"""processor p16f628a
load s {cod}
p16f628a.frequency = 4000000
stimulus asynchronous_stimulus
initial_state 1
start_cycle 0
{{ {stimulus} }}
name rxs
end
node nrx
attach nrx rxs portb1
module library libgpsim_modules
module load FileRecorder rec
rec.digital = true
rec.file = "rb3.txt"
node nrb3
attach nrb3 portb3 rec.pin{jumper}
log on {log}
log w txreg
log w ccp1con
log w pr2
log w t2con
break c {end}
run
rec.file = "end.txt"
quit
""")
    subprocess.run(["gpsim", "-i", "-c", script], capture_output=True, text=True, timeout=60)
    replies, writes, cur, cycle = [], [], "", 0
    for row in open(log):
        m = re.match(r"0x([0-9A-F]+) p16f628a", row)
        if m:
            cycle = int(m.group(1), 16)
            continue
        m = re.search(r"Wrote: 0x([0-9A-F]+) to (\w+)\(", row)
        if not m:
            continue
        v, reg = int(m.group(1), 16), m.group(2)
        if reg == "txreg":
            if v == 10:
                replies.append((cycle, cur))
                cur = ""
            else:
                cur += chr(v)
        elif reg in ("ccp1con", "pr2", "t2con"):
            writes.append((cycle, reg, v))
    edges = []
    # The recorder writes each change twice, as a level (0/1) and as a voltage; the levels are the edges.
    for row in open(edges_file):
        c, v = (row.split() + ["", ""])[:2]
        if v in ("0", "1"):
            edges.append((int(c), int(v)))
    return replies, writes, edges


MS = 1000
vectors = [("*IDN?", "OK PICGATE PIC-1.0"), ("PING", "OK PONG"), ("STATE?", "OK STATE 0 OFF WDOG 1000"),
           ("FREQ 1000", "OK FREQ 1000"), ("STATE?", "OK STATE 1000 ON WDOG 1000"), ("OFF", "OK FREQ 0"),
           ("FREQ 0007", "OK FREQ 7"), ("FREQ 245", "OK FREQ 245"), ("FREQ 3333", "OK FREQ 3333"),
           ("FREQ 100000", "OK FREQ 100000"), ("FREQ 100001", "ERR 2 RANGE"), ("FREQ 0", "OK FREQ 0"),
           ("FREQ abc", "ERR 3 SYNTAX"), ("FREQ", "ERR 3 SYNTAX"), ("FREQ 1234567", "ERR 2 RANGE"),
           ("FREQ 5 6", "ERR 3 SYNTAX"), ("WDOG 0", "OK WDOG 0"), ("WDOG 49", "ERR 2 RANGE"), ("WDOG 60001", "ERR 2 RANGE"),
           ("WDOG 60000", "OK WDOG 60000"), ("WDOG 1000", "OK WDOG 1000"), ("FIRE", "ERR 1 UNKNOWN"),
           ("BURST 5 1000", "OK BURST 5"), ("STATE?", "OK STATE 0 OFF WDOG 1000"), ("BURST 0 1000", "ERR 2 RANGE"),
           ("BURST 1000001 1000", "ERR 2 RANGE"), ("BURST 5 0", "ERR 2 RANGE"), ("BURST 5 100001", "ERR 2 RANGE"),
           ("BURST 5", "ERR 3 SYNTAX"), ("BURST x 5", "ERR 3 SYNTAX"), ("BURST 5 1000 7", "ERR 3 SYNTAX"),
           ("BURST", "ERR 3 SYNTAX"), ("BURST 1000000 100000", "OK BURST 1000000"), ("OFF", "OK FREQ 0"),
           ("PING\r", "OK PONG"), ("A" * 30, "ERR 1 UNKNOWN"), ("PING", "OK PONG"),
           ("BURST 1000 3333", "OK BURST 1000"), ("STATE?", "OK STATE 3333 ON WDOG 1000"), ("OFF", "OK FREQ 0")]
# Each run of five starts the chip afresh: a line that needs the one before it shares its run (indices 5k..5k+4).
figures = []


def rises(edges, a, b):
    """Rising edges of RB3 in [a, b)."""
    return [c for c, v in edges if v == 1 and a <= c < b]


def periods(r):
    return sorted(set(y - x for x, y in zip(r, r[1:])))


# The protocol's vectors, five lines to a gpsim run (a long stimulus is slow to read), 60 ms apart (the PIC answers
# while it receives nothing: the host waits for each reply).
got, runs = [], []
for i in range(0, len(vectors), 5):
    batch = [(20 * MS + (k + 1) * 60 * MS, text) for k, (text, _) in enumerate(vectors[i:i + 5])]
    replies, w, e = run(batch, batch[-1][0] + 60 * MS)
    got += [t for _, t in replies]
    runs.append((batch, w, e))
check(got == [w for _, w in vectors], "Wire_CommandsAndErrors_RepliesAsProtocol",
      "; ".join(f"{l!r}: got {g!r}, want {w!r}" for (l, w), g in zip(vectors, got + [None] * len(vectors)) if g != w))


def line_window(text):
    """(the line's last stop bit, the next line's, the run's writes and edges) for a line of the vectors."""
    for batch, w, e in runs:
        for k, (a, t) in enumerate(batch):
            if t == text:
                return a, (batch[k + 1][0] if k + 1 < len(batch) else a + 60 * MS), w, e


# Every FREQ's train, from RB3's edges: the period on the Timer2 grid, 2 us pulses, the first pulse after the line.
def started(w, a):
    """When the train a line asked for began: Timer2 switched on after the line (the old train runs until then)."""
    return next(c for c, r_, v in w if r_ == "t2con" and v & 4 and c > a)


for text, want in (("FREQ 1000", 1000), ("FREQ 245", 4080), ("FREQ 3333", 300), ("FREQ 100000", 10)):
    a, b, w, e = line_window(text)
    r = rises(e, started(w, a), b)
    widths = sorted(set(f - x for x in r for f in [next(c for c, v in e if v == 0 and c > x)]))
    hz = int(text.split()[1])
    check(len(r) > 3 and periods(r) == [want], f"{text.replace(' ', '')}_Edges_PeriodOnGrid", f"periods {periods(r)}")
    check(widths == [2], f"{text.replace(' ', '')}_Edges_Pulse2us", f"widths {widths}")
    if r:
        figures.append(f"{text}: {len(r)} pulses, period {want} us ({1e6 / want:.2f} Hz, error "
                       f"{(want - 1e6 / hz) * 1000:+.0f} ns), first pulse {r[0] - a} us after the line's last stop bit")
a, b, w, e = line_window("OFF")
stop = next(c for c, r_, v in w if r_ == "ccp1con" and v == 0 and c > a)
check(not rises(e, a + 1, b), "Off_Edges_NoPulseAfter", str(rises(e, a + 1, b)[:3]))
figures.append(f"OFF: PWM stopped {stop - a} us after the line's last stop bit")
a, b, w, e = line_window("BURST 5 1000")
check(len(rises(e, a, b)) == 5, "Burst5At1kHz_Edges_FivePulsesThenStateOff", str(len(rises(e, a, b))))

# Low frequencies (k Timer2 periods a pulse period) and counted bursts, one run: each line after the last burst ended.
t = 20 * MS
plan = [("WDOG 0", None, None, 0)]
for n, hz in ((3, 1), (3, 7), (1, 1000), (120, 1000), (1, 3333), (120, 3333), (1, 100000), (120, 100000),
              (256, 100000), (257, 100000), (65537, 100000)):
    plan.append((f"BURST {n} {hz}", n, hz, n / hz * 1e6))
lines, at = [], t
for text, n, hz, dur in plan:
    lines.append((at, text))
    at += int(dur) + 50 * MS
replies, w, e = run(lines, at)
check([x for _, x in replies] == ["OK WDOG 0"] + [f"OK BURST {n}" for _, n, _, _ in plan[1:]], "Burst_Replies_OkBurstN",
      str([x for _, x in replies]))
for k, (text, n, hz, dur) in enumerate(plan[1:], 1):
    a = lines[k][0]
    b = lines[k + 1][0] if k + 1 < len(lines) else at
    r = rises(e, a, b)
    grid = {1: 1000000, 7: 142856, 1000: 1000, 3333: 300, 100000: 10}[hz]
    name = f"Burst{n}At{hz}Hz_Edges_CountExactPeriodOnGrid"
    check(len(r) == n and (n == 1 or periods(r) == [grid]), name, f"{len(r)} pulses, periods {periods(r)[:5]}")
    if r:
        # The overflow interrupt stops Timer2 (a T2CON write without TMR2ON) after the n-th pulse's rising edge: after
        # the pulse's 2 us and before the next period could begin.
        stop = next((c for c, r_, v in w if r_ == "t2con" and not v & 4 and c > r[-1]), None)
        lag = stop - r[-1] if stop is not None else None
        if hz == 100000:
            check(lag is not None and 2 <= lag < 10, f"Burst{n}At{hz}Hz_Stop_AfterLastPulseBeforeNextPeriod", str(lag))
        figures.append(f"{text}: {len(r)} pulses, period {periods(r) or '-'} us, first pulse {r[0] - a} us after "
                       f"the line's last stop bit, Timer2 stopped {lag} us after the last pulse began")

# A burst under way is ended by OFF, by FREQ and by another BURST.
t = 20 * MS
lines = [(t, "BURST 1000 1000"), (t + 60 * MS, "OFF"), (t + 120 * MS, "BURST 1000 1000"), (t + 180 * MS, "FREQ 3333"),
         (t + 240 * MS, "BURST 1000 1000"), (t + 300 * MS, "BURST 10 100000"), (t + 360 * MS, "OFF")]
replies, w, e = run(lines, t + 400 * MS)
check([x for _, x in replies] == ["OK BURST 1000", "OK FREQ 0", "OK BURST 1000", "OK FREQ 3333", "OK BURST 1000",
                                  "OK BURST 10", "OK FREQ 0"], "BurstEnded_Replies", str([x for _, x in replies]))
r_off = rises(e, lines[1][0], lines[2][0])
check(len(rises(e, lines[0][0], lines[1][0])) < 1000 and r_off == [], "BurstEndedByOff_Edges_NoPulseAfterOff",
      f"{len(r_off)} pulses after OFF")
r_f = rises(e, started(w, lines[3][0]), lines[4][0])
check(len(r_f) > 100 and periods(r_f) == [300], "BurstEndedByFreq_Edges_FreqTrainOnly", f"periods {periods(r_f)[:5]}")
r_b = rises(e, started(w, lines[5][0]), lines[6][0])
check(len(r_b) == 10 and periods(r_b) == [10], "BurstEndedByBurst_Edges_SecondBurstCountExact",
      f"{len(r_b)} pulses, periods {periods(r_b)[:5]}")

# The watchdog: WDOG 50, FREQ 1000 (and a BURST), silence; STATE? twice.
t0 = 20 * MS
for cmd, ok in (("FREQ 1000", "OK FREQ 1000"), ("BURST 1000 1000", "OK BURST 1000")):
    replies, w, e = run([(t0, "WDOG 50"), (t0 + 40 * MS, cmd), (t0 + 200 * MS, "STATE?"), (t0 + 260 * MS, "STATE?")],
                        t0 + 320 * MS)
    start = next(c for c, r_, v in w if r_ == "t2con" and v & 4)
    stopped = next(c for c, r_, v in w if r_ == "ccp1con" and v == 0 and c > start)
    trip = stopped - (t0 + 40 * MS)
    r = rises(e, t0 + 40 * MS, t0 + 200 * MS)
    name = cmd.split()[0].title()
    check(50 * MS <= trip <= 52 * MS + 300 and r and r[-1] < stopped, f"Watchdog50ms{name}_Edges_OffBetween50And52ms",
          f"{trip / 1000:.3f} ms")
    check([x for _, x in replies] == ["OK WDOG 50", ok, "OK STATE 0 OFF WDOG 50 TRIPPED", "OK STATE 0 OFF WDOG 50"],
          f"Watchdog{name}_Tripped_StateSaysTrippedOnce", str([x for _, x in replies]))
    figures.append(f"watchdog 50 ms ({cmd}): train stopped {trip / 1000:.3f} ms after the last line's stop bit, "
                   f"last pulse {(r[-1] - t0 - 40 * MS) / 1000 if r else '-'} ms")

# The power-up watchdog, 1000 ms (977 ticks of 1.024 ms).
replies, w, e = run([(t0, "FREQ 1000")], t0 + 1100 * MS)
start = next(c for c, r_, v in w if r_ == "t2con" and v & 4)
stopped = next((c for c, r_, v in w if r_ == "ccp1con" and v == 0 and c > start), None)
trip = (stopped - t0) if stopped else None
check(trip is not None and 1000 * MS <= trip <= 1002 * MS + 300, "WatchdogPowerUp_Edges_OffBetween1000And1002ms",
      str(trip))
figures.append(f"watchdog at power-up (1000 ms): train stopped {trip / 1000 if trip else '-'} ms after the last line")

# PINGs every 40 ms keep it firing.
pings = [(t0 + 40 * MS + k * 40 * MS, "PING") for k in range(1, 5)]
replies, w, e = run([(t0, "WDOG 50"), (t0 + 40 * MS, "FREQ 1000")] + pings, t0 + 300 * MS)
stopped = [c for c, r_, v in w if r_ == "ccp1con" and v == 0 and c > t0 + 41 * MS]
check(len(stopped) == 1 and stopped[0] - pings[-1][0] >= 49 * MS, "Watchdog_PingedEvery40ms_OffOnlyAfterLastPing",
      str([(c - pings[-1][0]) / 1000 for c in stopped]))

print("\n".join(figures))
print(f"pic (gpsim): {passed} passed, {failed} failed")
sys.exit(1 if failed else 0)
