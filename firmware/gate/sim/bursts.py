"""What differential.py and pty_bursts.py share: the AVR image's period grid and how its pulses are grouped by the line
that started their train (docs/gate-firmware.md, "The twin agrees")."""


def hz_of(text):
    """The frequency a FREQ or BURST line asks for; 0 for OFF and anything else."""
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


def group(lines, rises):
    """Every FREQ, OFF and BURST line of `lines` ((cycle, text), in order) with the pulses (`rises`, rising-edge cycles)
    it fired and its first pulse's cycle: (freq, counts), freq a list of (index, cycle, text), counts {index: [pulses,
    first]}.

    A pulse belongs to the line whose command started its train: a train is a run of pulses one fired period apart, and
    the line that started it is the last frequency line to arrive before its first pulse (a line takes milliseconds to
    arrive, its first pulse comes within 0.21 ms). Pulses of a train still under way when the next line arrives (before
    that line has been processed) stay with the line that started the train; pulses before any line are nobody's."""
    freq = [(i, at, text) for i, (at, text) in enumerate(lines) if text.split(" ")[0].upper() in ("FREQ", "OFF", "BURST")]
    counts = {i: [0, None] for i, _, _ in freq}
    k, prev, period, owner = -1, None, None, None
    for r in rises:
        if prev is None or period is None or abs(r - prev - period) > 16:
            while k + 1 < len(freq) and freq[k + 1][1] < r:
                k += 1
            if k < 0:
                continue
            owner = freq[k][0]
            period = fired_period(hz_of(freq[k][2])) if hz_of(freq[k][2]) else None
            if counts[owner][1] is None:
                counts[owner][1] = r
        counts[owner][0] += 1
        prev = r
    return freq, counts
