#!/usr/bin/env python3
"""The PIC16F628A subset image in gpsim against the protocol's vectors it implements (make -C firmware/gate test-pic).

    pic_vectors.py GATE.cod WORKDIR

The host's lines go in as a bit-level stimulus on RB1/RX at 9600 baud (gpsim's USART receives them as a PIC would);
every write to TXREG (the replies), CCP1CON, PR2 and T2CON (the PWM started and stopped) is logged by gpsim with its
instruction cycle (1 us at 4 MHz). gpsim here does not give the RB3 pin's edges, so the pulse train is checked by the
PWM settings written and the instant Timer2 was started or stopped, not by its edges. Prints one line per failed check,
the figures, and "pic (gpsim): N passed, N failed"."""
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
    edges_file = f"{work}/rb3.txt"
    jumper = " portb6" if jumper else ""
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
rec.file = "{edges_file}"
node nrb3
attach nrb3 portb3 rec.pin{jumper}
log on {log}
log w txreg
log w ccp1con
log w pr2
log w t2con
break c {end}
run
rec.file = "{work}/closed.txt"
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
vectors = [("*IDN?", "OK PICGATE PIC-0.1"), ("PING", "OK PONG"), ("STATE?", "OK STATE 0 OFF WDOG 1000"),
           ("FREQ 1000", "OK FREQ 1000"), ("STATE?", "OK STATE 1000 ON WDOG 1000"), ("OFF", "OK FREQ 0"),
           ("FREQ 0007", "ERR 2 RANGE"), ("FREQ 245", "OK FREQ 245"), ("FREQ 3333", "OK FREQ 3333"),
           ("FREQ 100000", "OK FREQ 100000"), ("FREQ 100001", "ERR 2 RANGE"), ("FREQ 0", "OK FREQ 0"),
           ("FREQ abc", "ERR 3 SYNTAX"), ("FREQ", "ERR 3 SYNTAX"), ("FREQ 1234567", "ERR 2 RANGE"),
           ("WDOG 0", "OK WDOG 0"), ("WDOG 49", "ERR 2 RANGE"), ("WDOG 60001", "ERR 2 RANGE"), ("WDOG 60000", "OK WDOG 60000"),
           ("WDOG 1000", "OK WDOG 1000"), ("FIRE", "ERR 1 UNKNOWN"), ("BURST 5 1000", "ERR 1 UNKNOWN"),
           ("PING\r", "OK PONG"), ("A" * 30, "ERR 1 UNKNOWN"), ("PING", "OK PONG")]
# gpsim reads a long stimulus slowly (minutes for 25 lines), so the vectors go in five to a run.
lines, got, writes = [], [], []
for i in range(0, len(vectors), 5):
    batch = [(20 * MS + (k + 1) * 60 * MS, text) for k, (text, _) in enumerate(vectors[i:i + 5])]
    replies, w, _ = run(batch, batch[-1][0] + 60 * MS)
    got += [t for _, t in replies]
    # Instants relative to the batch; one PWM set-up per batch at most is read below, so keep each batch's own.
    lines.append((batch, w))
check(got == [w for _, w in vectors], "Wire_SubsetCommandsAndErrors_RepliesAsProtocol",
      "; ".join(f"{l!r}: got {g!r}, want {w!r}" for (l, w), g in zip(vectors, got + [None] * len(vectors)) if g != w))

# The PWM each FREQ set up: Timer2 prescaler (T2CON bits 1:0) and PR2 give the period; the first pulse begins at the
# timer's first increment after T2CON is written (one prescaled tick).
figures = []
def batch_of(text):
    return next((a, w) for batch, w in lines for a, t in batch if t == text)


for text, want_period in (("FREQ 1000", 1000), ("FREQ 245", 4080), ("FREQ 3333", 300), ("FREQ 100000", 10)):
    line_at, writes = batch_of(text)
    after = [w for w in writes if w[0] > line_at]
    pr2 = next(v for c, r, v in after if r == "pr2")
    t2con_at, t2con = next((c, v) for c, r, v in after if r == "t2con" and v & 4)
    presc = (1, 4, 16, 16)[t2con & 3]
    period = (pr2 + 1) * presc
    hz = int(text.split()[1])
    check(period == want_period, f"{text.replace(' ', '')}_Pwm_PeriodOnGrid", f"{period} us")
    figures.append(f"{text}: PR2 {pr2}, prescaler 1:{presc}, period {period} us ({1e6 / period:.2f} Hz, error "
                   f"{(period - 1e6 / hz) * 1000:+.0f} ns); Timer2 started {t2con_at - line_at} us after the line's "
                   f"last stop bit, the first pulse {presc} us later")
off_at, writes = batch_of("OFF")
stop = next(c for c, r, v in writes if r == "ccp1con" and v == 0 and c > off_at)
figures.append(f"OFF: PWM stopped {stop - off_at} us after the line's last stop bit")

# The watchdog: WDOG 50, FREQ 1000, silence; STATE? twice.
t0 = 20 * MS
replies, writes, _ = run([(t0, "WDOG 50"), (t0 + 40 * MS, "FREQ 1000"), (t0 + 200 * MS, "STATE?"), (t0 + 260 * MS, "STATE?")],
                      t0 + 320 * MS)
start = next(c for c, r, v in writes if r == "t2con" and v & 4)
stopped = next(c for c, r, v in writes if r == "ccp1con" and v == 0 and c > start)
trip = stopped - (t0 + 40 * MS)
check(50 * MS <= trip <= 51 * MS + 100, "Watchdog_50ms_TripsBetween50And51ms", f"{trip / 1000:.3f} ms")
check([t for _, t in replies] == ["OK WDOG 50", "OK FREQ 1000", "OK STATE 0 OFF WDOG 50 TRIPPED", "OK STATE 0 OFF WDOG 50"],
      "Watchdog_Tripped_StateSaysTrippedOnce", str([t for _, t in replies]))
figures.append(f"watchdog 50 ms: PWM stopped {trip / 1000:.3f} ms after the last line's stop bit")

# PINGs every 40 ms keep it firing.
pings = [(t0 + 40 * MS + k * 40 * MS, "PING") for k in range(1, 5)]
replies, writes, _ = run([(t0, "WDOG 50"), (t0 + 40 * MS, "FREQ 1000")] + pings, t0 + 300 * MS)
stopped = [c for c, r, v in writes if r == "ccp1con" and v == 0 and c > t0 + 41 * MS]
check(len(stopped) == 1 and stopped[0] - pings[-1][0] >= 49 * MS, "Watchdog_PingedEvery40ms_OffOnlyAfterLastPing",
      str([(c - pings[-1][0]) / 1000 for c in stopped]))

print("\n".join(figures))
print(f"pic (gpsim): {passed} passed, {failed} failed")
sys.exit(1 if failed else 0)
