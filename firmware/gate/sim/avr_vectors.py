#!/usr/bin/env python3
"""The AVR gate image in simavr against the protocol's vectors, measured cycle by cycle (make -C firmware/gate test-avr).

    avr_vectors.py GATE_SIM GATE.elf FIGURES_OUT

Each scenario is a script of lines, each arriving at a cycle (its last byte's stop bit, as gate_sim defines it); the
gate's replies and every edge of its pulse pin come back with their cycles. Everything is in simulated cycles at
16 MHz, so every run gives the same figures. Prints one line per failed check, the measured figures, and
"avr (simavr): N passed, N failed"; exits 1 on any failure. The figures are also written to FIGURES_OUT."""
import subprocess
import sys
import tempfile

F = 16_000_000
MS = F // 1000
# simavr reports an edge at the instruction boundary after the timer's exact cycle (an interrupt's entry is 4-5
# cycles, the longest instruction 4): an edge may read up to this many cycles late.
EDGE_SLACK = 8

gate_sim, elf, figures_out = sys.argv[1], sys.argv[2], sys.argv[3]
passed = failed = 0
figures = []


def check(ok, name, detail=""):
    global passed, failed
    if ok:
        passed += 1
    else:
        failed += 1
        print(f"FAIL {name}: {detail}")


def run(lines, end):
    """lines: [(cycle, text)]; returns (replies [(cycle, text)], rises [cycle], falls [cycle])."""
    for (a, _), (b, text) in zip(lines, lines[1:]):
        # A line's bytes go in one after another, ending at its cycle: two lines must not overlap on the wire.
        assert b - a >= (len(text) + 1) * 18304, f"{text!r} at {b} overlaps the line before it"
    with tempfile.NamedTemporaryFile("w", suffix=".txt", delete=False) as script:
        for at, text in lines:
            script.write(f"{at} {text}\n")
        script.write(f"end {end}\n")
    out = subprocess.run([gate_sim, elf, script.name], capture_output=True, text=True, check=True).stdout
    replies, rises, falls = [], [], []
    level = 0
    for row in out.splitlines():
        parts = row.split(" ", 2)
        if parts[0] == "reply":
            replies.append((int(parts[1]), parts[2] if len(parts) > 2 else ""))
        elif parts[0] == "edge":
            v = int(parts[2])
            if v != level:
                (rises if v else falls).append(int(parts[1]))
                level = v
    return replies, rises, falls


def texts(replies):
    return [t for _, t in replies]


def between(cycles, a, b):
    return [c for c in cycles if a <= c < b]


def us(cycles):
    return cycles / 16.0


def fired_period(hz):
    """The firmware's grid (atmega328p/main.c, fired_period_cycles): cycles per period."""
    i = 0 if hz >= 245 else 1 if hz >= 31 else 2 if hz >= 4 else 3
    p = (1, 8, 64, 256)[i]
    return ((F // p + hz // 2) // hz) * p


# --- every command and every error, on the wire ---------------------------------------------------------------------
vectors = [
    ("*IDN?", "OK PICGATE AVR-1.1"), ("STATE?", "OK STATE 0 OFF WDOG 1000"), ("PING", "OK PONG"),
    ("FREQ 1000", "OK FREQ 1000"), ("STATE?", "OK STATE 1000 ON WDOG 1000"), ("OFF", "OK FREQ 0"),
    ("FREQ 100000", "OK FREQ 100000"), ("FREQ 0", "OK FREQ 0"), ("WDOG 0", "OK WDOG 0"), ("WDOG 50", "OK WDOG 50"),
    ("WDOG 60000", "OK WDOG 60000"), ("WDOG 1000", "OK WDOG 1000"), ("BURST 2 1000", "OK BURST 2"),
    ("freq +0007", "OK FREQ 7"), ("OFF", "OK FREQ 0"), (" \\tPING \\r", "OK PONG"),
    ("FIRE", "ERR 1 UNKNOWN"), ("FREQX 5", "ERR 1 UNKNOWN"), ("FREQ 100001", "ERR 2 RANGE"), ("FREQ -1", "ERR 2 RANGE"),
    ("FREQ abc", "ERR 3 SYNTAX"), ("FREQ", "ERR 3 SYNTAX"), ("FREQ 1 2", "ERR 3 SYNTAX"), ("OFF 3", "ERR 3 SYNTAX"),
    ("FREQ 2147483648", "ERR 3 SYNTAX"), ("WDOG 49", "ERR 2 RANGE"), ("WDOG 60001", "ERR 2 RANGE"),
    ("WDOG x", "ERR 3 SYNTAX"), ("BURST 0 1000", "ERR 2 RANGE"), ("BURST 1000001 1000", "ERR 2 RANGE"),
    ("BURST 5 0", "ERR 2 RANGE"), ("BURST 5 100001", "ERR 2 RANGE"), ("BURST 5", "ERR 3 SYNTAX"),
    ("BURST 5 x", "ERR 3 SYNTAX"), ("P\\xc3\\xafNG", "ERR 1 UNKNOWN"), ("FREQ 1\\xff0", "ERR 3 SYNTAX"),
    ("PING" + " " * 124, "OK PONG"), ("PING" + " " * 125, "ERR 1 UNKNOWN"), ("A" * 400, "ERR 1 UNKNOWN"),
    ("PING", "OK PONG"),
]
# 60 ms apart: the longest reply (29 bytes) takes 33 ms on simavr's wire; the 400-byte line takes 460 ms to arrive.
at, lines = 100 * MS, []
for text, _ in vectors:
    at += 60 * MS + (len(text) * 18304 if len(text) > 100 else 0)
    lines.append((at, text))
replies, rises, _ = run(lines, at + 60 * MS)
check(texts(replies) == [want for _, want in vectors], "Wire_EveryCommandAndError_RepliesAsProtocol",
      "\n  " + "\n  ".join(f"{line!r}: got {got!r}, want {want!r}" for (line, want), got
                             in zip(vectors, texts(replies) + [None] * len(vectors)) if got != want))
# The empty line is heard but not answered.
replies, _, _ = run([(100 * MS, ""), (120 * MS, "PING")], 160 * MS)
check(texts(replies) == ["OK PONG"], "Wire_EmptyLine_NoReply", str(texts(replies)))

# --- bursts: exact counts, at every prescaler, and under UART traffic ------------------------------------------------
first_pulse = []
for n, hz in [(5, 1000), (3, 100000), (4, 3333), (1, 100000), (1000, 100000), (7, 50), (2, 5), (1, 1)]:
    t0 = 100 * MS
    span = int(n * F / hz) + 40 * MS
    replies, rises, falls = run([(t0, f"BURST {n} {hz}"), (t0 + span, "STATE?")], t0 + span + 60 * MS)
    got = len(between(rises, t0, t0 + span))
    check(got == n, f"Burst_{n}At{hz}Hz_FiresExactly{n}", f"fired {got}")
    check(len(rises) == len(falls), f"Burst_{n}At{hz}Hz_EndsLow", f"{len(rises)} rises, {len(falls)} falls")
    check(texts(replies) == [f"OK BURST {n}", "OK STATE 0 OFF WDOG 1000"], f"Burst_{n}At{hz}Hz_ThenStateOff",
          str(texts(replies)))
    if rises:
        first_pulse.append((f"BURST {n} {hz}", rises[0] - t0))
        if n > 1:
            per = (rises[-1] - rises[0]) / (n - 1)
            check(abs(per - fired_period(hz)) <= EDGE_SLACK, f"Burst_{n}At{hz}Hz_PeriodOnGrid",
                  f"{per} cycles, grid {fired_period(hz)}")

# 10000 pulses at 100 kHz while PING lines arrive every 5 ms: the receive and tick interrupts never let a pulse slip.
t0 = 100 * MS
pings = [(t0 + k * 8 * MS + 7 * k, "PING") for k in range(3, 15)]
replies, rises, _ = run([(t0, "BURST 10000 100000")] + pings, t0 + 160 * MS)
check(len(rises) == 10000, "Burst_10000At100kHzUnderPings_FiresExactly10000", f"fired {len(rises)}")
check(texts(replies) == ["OK BURST 10000"] + ["OK PONG"] * 12, "Burst_10000At100kHzUnderPings_EveryPingAnswered",
      str(texts(replies)[:3]))

# A burst ended by a later frequency command.
t0 = 100 * MS
replies, rises, _ = run([(t0, "BURST 1000 1000"), (t0 + 5 * MS + MS // 2, "OFF")], t0 + 100 * MS)
check(len(rises) == 6, "Burst_ThenOffAt5point5ms_SixPulsesThenNone", f"fired {len(rises)}")
replies, rises, _ = run([(t0, "BURST 100 1000"), (t0 + 30 * MS + MS // 2, "BURST 3 100000")], t0 + 200 * MS)
check(len(rises) == 34, "Burst_ThenBurst3_ThirtyOneThenThree", f"fired {len(rises)}")
replies, rises, _ = run([(t0, "BURST 100 1000"), (t0 + 20 * MS + MS // 2, "FREQ 2000")], t0 + 200 * MS)
after = between(rises, t0 + 20 * MS + MS // 2, t0 + 200 * MS)
check(len(rises) - len(after) == 21 and len(after) >= 350, "Burst_ThenFreq2000_FiresOnUncounted",
      f"{len(rises) - len(after)} before, {len(after)} after")
replies, rises, _ = run([(t0, "BURST 30 1000"), (t0 + 10 * MS + MS // 2, "PING")], t0 + 100 * MS)
check(len(rises) == 30, "Burst_ThenPing_CountHolds", f"fired {len(rises)}")

# --- periods and pulse width -----------------------------------------------------------------------------------------
for hz in (1000, 3333, 100000, 245, 244, 31, 1):
    t0 = 100 * MS
    length = max(50 * MS, 3 * F // hz)
    replies, rises, falls = run([(t0, "WDOG 0"), (t0 + 40 * MS, f"FREQ {hz}")], t0 + 40 * MS + length)
    t1 = t0 + 40 * MS
    first_pulse.append((f"FREQ {hz}", rises[0] - t1))
    k = len(rises)
    per = (rises[-1] - rises[0]) / (k - 1)
    ideal = F / hz
    grid = fired_period(hz)
    check(abs(per - grid) <= EDGE_SLACK / (k - 1) + 0.01, f"Freq{hz}_MeanPeriod_OnGrid", f"{per} cycles, grid {grid}")
    widths = [f - r for r, f in zip(rises, falls)]
    want_width = max(32, (1, 8, 64, 256)[0 if hz >= 245 else 1 if hz >= 31 else 2 if hz >= 4 else 3])
    check(all(abs(w - want_width) <= EDGE_SLACK for w in widths), f"Freq{hz}_PulseWidth_{want_width}Cycles",
          f"{min(widths)}..{max(widths)}")
    jitter = max(abs((r - rises[0]) - i * grid) for i, r in enumerate(rises))
    figures.append(f"FREQ {hz}: fired period {grid} cycles = {grid / 16:.4f} us ({F / grid:.3f} Hz), requested "
                   f"{ideal / 16:.4f} us: error {(grid - ideal) / 16 * 1000:+.2f} ns ({(grid - ideal) / ideal * 1e6:+.1f} ppm); "
                   f"measured mean {per:.3f} cycles over {k} pulses, edges within {jitter:.0f} cycles of the grid; "
                   f"pulse {min(widths)}..{max(widths)} cycles")

# --- first-pulse delay: the line's last stop bit to the first rising edge --------------------------------------------
delays = [d for _, d in first_pulse]
check(all(0 < d < 4000 for d in delays), "FirstPulse_AnyCommand_Within250us", str(first_pulse))
figures.append("first pulse after the line's last stop bit: " + ", ".join(f"{name} {d} cycles ({us(d):.1f} us)"
                                                                           for name, d in first_pulse))
figures.append(f"first pulse delay: min {min(delays)} cycles ({us(min(delays)):.1f} us), max {max(delays)} cycles "
               f"({us(max(delays)):.1f} us)")

# --- scheduled bursts (BURST <n> <hz> AFTER <us>): the first pulse <us> after the line's last stop bit ----------------
# The error is the first rising edge less (the line's cycle + us x 16). The image arms Timer0's compare START_TICKS early
# for its interrupt's entry; what is left is the time base's 0.5 us tick and the interrupts that may delay the compare's
# (the reply being sent, the 1 ms tick, Timer0's overflow).
after_errors = []
for us_after in (300, 1000, 5000, 20000, 100000, 1000000):
    for n, hz in ((120, 1000), (3, 100000)):
        for phase in (0, 5, 11, 777, 5003):  # the line's arrival at other phases of the ms tick and the time base
            t0 = 100 * MS + phase
            span = us_after * 16 + int(n * F / hz) + 60 * MS
            lines = [(t0, "WDOG 0"), (t0 + 40 * MS, f"BURST {n} {hz} AFTER {us_after}")]
            t1 = t0 + 40 * MS
            replies, rises, falls = run(lines, t1 + span)
            ok = texts(replies) == ["OK WDOG 0", f"OK BURST {n} AFTER {us_after}"]
            check(ok, f"BurstAfter{us_after}_{n}At{hz}Hz_Acknowledged", str(texts(replies)))
            check(len(rises) == n and len(falls) == n, f"BurstAfter{us_after}_{n}At{hz}Hz_FiresExactly{n}", f"fired {len(rises)}")
            if rises:
                after_errors.append((us_after, rises[0] - t1 - us_after * 16))
for us_after in sorted({u for u, _ in after_errors}):
    errs = [e for u, e in after_errors if u == us_after]
    figures.append(f"BURST ... AFTER {us_after}: first pulse {us_after} us {'+' if min(errs) >= 0 else ''}{us(min(errs)):.2f}.."
                   f"{us(max(errs)):+.2f} us after the line's last stop bit ({min(errs)}..{max(errs)} cycles, {len(errs)} runs)")
errs = [e for u, e in after_errors if u >= 300]
check(all(-16 <= e <= 40 for e in errs), "BurstAfter_300usAndMore_WithinTickAndInterrupts",
      f"errors {min(errs)}..{max(errs)} cycles")
figures.append(f"scheduled burst, 300 us and more: error {us(min(errs)):+.2f}..{us(max(errs)):+.2f} us over {len(errs)} runs")

# Shorter than the gate's processing: the first pulse as soon as the line is processed, as a plain BURST.
t0 = 100 * MS
replies, rises, _ = run([(t0, "BURST 3 1000 AFTER 0")], t0 + 60 * MS)
check(texts(replies) == ["OK BURST 3 AFTER 0"] and len(rises) == 3, "BurstAfter0_FiresWhenProcessed", str(texts(replies)))
if rises:
    figures.append(f"BURST 3 1000 AFTER 0: first pulse {us(rises[0] - t0):.1f} us after the line (the processing)")

# A later frequency command cancels the waiting start; a PING does not.
replies, rises, _ = run([(t0, "BURST 5 1000 AFTER 50000"), (t0 + 20 * MS, "OFF")], t0 + 120 * MS)
check(len(rises) == 0 and texts(replies) == ["OK BURST 5 AFTER 50000", "OK FREQ 0"], "BurstAfter_ThenOff_NeverFires",
      f"{len(rises)} pulses, {texts(replies)}")
replies, rises, _ = run([(t0, "BURST 5 1000 AFTER 50000"), (t0 + 20 * MS, "BURST 2 1000")], t0 + 120 * MS)
check(len(rises) == 2 and rises[0] < t0 + 21 * MS, "BurstAfter_ThenBurst_OnlyTheNewOne", f"{len(rises)} pulses")
replies, rises, _ = run([(t0, "BURST 5 1000 AFTER 50000"), (t0 + 20 * MS, "PING")], t0 + 120 * MS)
check(len(rises) == 5 and abs(rises[0] - t0 - 50000 * 16) <= 40, "BurstAfter_ThenPing_FiresOnTime", f"{len(rises)} pulses")
# The watchdog watches the wait: WDOG 50 and a start 100 ms away never fires.
replies, rises, _ = run([(t0, "WDOG 50"), (t0 + 40 * MS, "BURST 5 1000 AFTER 100000"), (t0 + 200 * MS, "STATE?")],
                        t0 + 260 * MS)
check(len(rises) == 0 and texts(replies)[-1] == "OK STATE 0 OFF WDOG 50 TRIPPED", "BurstAfter_WatchdogDuringWait_NeverFires",
      f"{len(rises)} pulses, {texts(replies)}")
replies, _, _ = run([(t0, "CAPS?")], t0 + 60 * MS)
check(texts(replies) == ["OK CAPS AFTER"], "Caps_Asked_ListsAfter", str(texts(replies)))

# --- the watchdog ----------------------------------------------------------------------------------------------------
t0 = 100 * MS
replies, rises, _ = run([(t0, "WDOG 50"), (t0 + 40 * MS, "FREQ 100000"), (t0 + 200 * MS, "STATE?"),
                         (t0 + 260 * MS, "STATE?")], t0 + 320 * MS)
t1 = t0 + 40 * MS
last = max(between(rises, t1, t0 + 200 * MS))
stop_from, stop_to = last - t1, last + 1600 - t1
check(50 * MS <= stop_to and stop_from <= 51 * MS + 2000, "Watchdog_50ms_TripsBetween50And51ms",
      f"stopped {us(stop_from) / 1000:.3f}..{us(stop_to) / 1000:.3f} ms after the line")
check(texts(replies)[2:] == ["OK STATE 0 OFF WDOG 50 TRIPPED", "OK STATE 0 OFF WDOG 50"],
      "Watchdog_Tripped_StateSaysTrippedOnce", str(texts(replies)))
figures.append(f"watchdog 50 ms: the train stopped {us(stop_from) / 1000:.3f}..{us(stop_to) / 1000:.3f} ms after the "
               f"last line's stop bit (last pulse + one 10 us period)")

pings = [(t0 + 40 * MS + k * 40 * MS, "PING") for k in range(1, 6)]
replies, rises, _ = run([(t0, "WDOG 50"), (t0 + 40 * MS, "FREQ 1000")] + pings, t0 + 400 * MS)
last_ping = pings[-1][0]
check(len(between(rises, t0 + 40 * MS, last_ping)) >= 199, "Watchdog_PingedEvery40ms_FiresOn",
      f"{len(between(rises, t0 + 40 * MS, last_ping))} pulses")
tail = between(rises, last_ping, t0 + 400 * MS)
check(len(tail) in (50, 51), "Watchdog_PingsStop_Off50msAfterLastPing", f"{len(tail)} pulses after the last PING")

replies, rises, _ = run([(t0, "FREQ 100000"), (t0 + 1100 * MS, "STATE?")], t0 + 1160 * MS)
last = max(rises)
stop_from, stop_to = last - t0, last + 1600 - t0
check(1000 * MS <= stop_to and stop_from <= 1001 * MS + 2000, "Watchdog_PowerUp1000ms_TripsBetween1000And1001ms",
      f"{us(stop_from) / 1000:.3f}..{us(stop_to) / 1000:.3f} ms")
check(texts(replies) == ["OK FREQ 100000", "OK STATE 0 OFF WDOG 1000 TRIPPED"], "Watchdog_PowerUp_Tripped",
      str(texts(replies)))
figures.append(f"watchdog 1000 ms (power-up): stopped {us(stop_from) / 1000:.3f}..{us(stop_to) / 1000:.3f} ms after the line")

with open(figures_out, "w") as f:
    f.write("\n".join(figures) + "\n")
print("\n".join(figures))
print(f"avr (simavr): {passed} passed, {failed} failed")
sys.exit(1 if failed else 0)
