/* The gate's portable core: line parser, command table, burst counter, watchdog (docs/laser-gate-protocol.md).
 *
 * No hardware here. A chip's layer (atmega328p/, the native tests' fake) gives the core a small HAL: start or stop
 * the pulse train, and send a reply line. The chip layer calls:
 *   gate_byte(g, b)        for every byte received, in order (from the main loop, not an interrupt);
 *   gate_pulse(g)          from its timer interrupt after every pulse of a burst; it returns 1 when the burst's count
 *                          is reached, and the chip layer must then stop the train before the next pulse begins;
 *   gate_poll(g, now_ms)   often (every pass of the main loop), with a free-running millisecond count: it folds in a
 *                          burst that ended by itself and runs the watchdog.
 * The semantics follow the twin (src/LaserEngrave.Simulator/LaserGate/VirtualLaserGate.cs) byte for byte: the same
 * replies, the same 128-byte line limit, the same reading of signs, whitespace and non-ASCII bytes. */
#ifndef GATE_CORE_H
#define GATE_CORE_H

#include <stdint.h>

#define GATE_MAX_HZ 100000UL
#define GATE_MAX_BURST 1000000UL
#define GATE_MIN_WDOG_MS 50UL
#define GATE_MAX_WDOG_MS 60000UL
/* Longest delay of a scheduled burst (BURST <n> <hz> AFTER <us>), microseconds. */
#define GATE_MAX_AFTER_US 1000000UL
/* Longest line kept (bytes before the '\n', a '\r' included); a longer one is answered ERR 1 UNKNOWN, as the twin does. */
#define GATE_LINE_MAX 128

typedef struct gate_hal {
    /* Fire at hz pulses/s (hz 0: stop at once, the output low). pulses 0: until told otherwise; pulses > 0: the chip
     * calls gate_pulse after each pulse and stops when it returns 1. The first pulse begins at once. */
    void (*fire)(uint32_t hz, uint32_t pulses);
    /* Queue one reply line (text without the line end; the HAL adds '\n'). Must not block for long. */
    void (*send)(const char *text);
    /* As fire (hz > 0), but the first pulse begins after_us microseconds after the line being handled now was received
     * (the HAL's own stamp of its last byte, taken in its receive interrupt), timed by a hardware timer; at once when
     * that time has already passed. fire(0, 0) cancels a start still waiting. NULL on a chip without it: the gate then
     * refuses BURST ... AFTER with ERR 3 SYNTAX, as a gate older than it does, and CAPS? does not list AFTER. */
    void (*fire_after)(uint32_t hz, uint32_t pulses, uint32_t after_us);
} gate_hal;

typedef struct gate {
    const gate_hal *hal;
    const char *firmware;        /* "AVR-1.0": the identification's last word */
    char line[GATE_LINE_MAX];
    uint8_t len;
    uint8_t overflow;
    uint32_t hz;                 /* frequency the gate fires at now (0: off) */
    uint32_t wdog_ms;            /* 0: disabled */
    uint32_t last_heard_ms;      /* millisecond count when the last line ended */
    uint32_t now_ms;             /* last count handed to gate_poll */
    uint8_t tripped;             /* the watchdog switched the laser off since the last STATE? */
    uint16_t trips;              /* how often (for tests) */
    volatile uint32_t burst_left;/* pulses still to fire in the burst under way (0: none) */
    volatile uint8_t burst_done; /* set by gate_pulse when the count is reached; folded in by gate_poll */
} gate;

void gate_init(gate *g, const gate_hal *hal, const char *firmware, uint32_t wdog_ms);
void gate_byte(gate *g, uint8_t b);
/* Inline, so that a chip's pulse interrupt stays short. */
static inline uint8_t gate_pulse(gate *g)
{
    uint32_t left = g->burst_left;
    if (left == 0) {
        return 0;
    }
    g->burst_left = --left;
    if (left == 0) {
        g->burst_done = 1;
        return 1;
    }
    return 0;
}
void gate_poll(gate *g, uint32_t now_ms);

/* Parses a decimal whole number as .NET's int.TryParse with a leading sign does ("+5", "-0", "007"; no spaces,
 * nothing beyond the int32 range). Returns 1 and the value, or 0. Exposed for the unit tests. */
uint8_t gate_parse_int(const char *s, uint8_t len, int32_t *value);

#endif
