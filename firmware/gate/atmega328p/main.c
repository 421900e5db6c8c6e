/* ATmega328P layer of the reference laser gate (docs/gate-firmware.md), 16 MHz crystal (Arduino Uno/Nano class).
 *
 *   PB1 / OC1A (Arduino D9)  pulse train, TTL, active high: Timer1 in fast PWM (mode 14, TOP = ICR1), so every pulse is
 *                            made by the timer's hardware, not by a software loop. Pulse width GATE_PULSE_NS (2 us; one
 *                            timer tick where the prescaler's tick is longer, below 245 Hz).
 *   PD0 / RXD, PD1 / TXD     USART0, 9600 baud 8N1 (UBRR 103: 9615 baud, +0.16 %), interrupt-driven both ways.
 *   Timer2                   1 ms tick (CTC, /128, OCR2A 124) for the watchdog.
 *   Timer0                   the time base of scheduled bursts (BURST <n> <hz> AFTER <us>): free-running at /8, 0.5 us a
 *                            tick, 32 bits with its overflow count. The receive interrupt stamps every line's last byte
 *                            on it; a scheduled start is a compare match (OCR0A) in the right overflow lap, whose
 *                            interrupt starts Timer1 (no busy loop waits for it).
 *
 * The frequency grid: a period is a whole number of timer ticks, ticks = round(16 MHz / (prescaler x hz)) with the
 * smallest prescaler of 1, 8, 64, 256 whose ticks fit 16 bits; the period fired is ticks x prescaler / 16 MHz
 * (fired_period_cycles() below; the table in docs/gate-firmware.md). Bursts are counted by the compare-match
 * interrupt at every pulse's falling edge; the n-th stops the clock before the next pulse can begin. */
#include <avr/io.h>
#include <avr/interrupt.h>
#include <avr/sleep.h>
#include <stdint.h>
#include "../core/gate_core.h"

#ifndef F_CPU
#define F_CPU 16000000UL
#endif
#define GATE_PULSE_CYCLES 32 /* 2 us at 16 MHz */
#define GATE_FIRMWARE "AVR-1.1"
/* Timer0 ticks (0.5 us) from a scheduled start's compare match to the first pulse's rising edge: the interrupt's entry and
 * the register writes of start_train (measured in simavr, make -C firmware/gate test-avr: "scheduled burst" figures). The
 * match is set that much before the time asked for. */
#define START_TICKS 18
/* A start due sooner than this (ticks) is not armed on the compare (its match could pass while it is being armed) but
 * waited for here, at most this long: 8 us. */
#define ARM_MARGIN_TICKS 16
#define GATE_WDOG_AT_POWER_UP 1000

static gate g;

/* ---- USART: ring buffers (sizes are powers of two) ---- */
static volatile uint8_t rx_buf[64], rx_head, rx_tail;
static volatile uint8_t tx_buf[128], tx_head, tx_tail;
static volatile uint32_t ms;

/* ---- Timer0: the time base, 0.5 us a tick ---- */
static volatile uint32_t t0_laps; /* Timer0 overflows: the time base's bits 8 and up */

ISR(TIMER0_OVF_vect) { t0_laps++; }

/* The time base now, in 0.5 us ticks. Interrupts off (an interrupt handler, or after cli). */
static uint32_t now_ticks(void)
{
    uint8_t t = TCNT0;
    uint32_t laps = t0_laps;
    if ((TIFR0 & _BV(TOV0)) && t < 128) laps++; /* wrapped, and its overflow interrupt has not run yet */
    return (laps << 8) | t;
}

/* Stamps of the lines' last bytes ('\n'), in the order they came, for the main loop to hand over with each line. */
static volatile uint32_t line_stamp[16];
static volatile uint8_t stamp_head, stamp_tail;
static uint32_t line_at; /* the stamp of the line the core handles now */

ISR(USART_RX_vect)
{
    uint32_t at = now_ticks(); /* first: the stamp is this interrupt's entry, a fixed time after the receive completed */
    uint8_t b = UDR0;
    uint8_t next = (uint8_t)((rx_head + 1) & 63);
    if (next == rx_tail) return; /* full: the byte is lost (the host sends one short line at a time) */
    if (b == '\n') {
        uint8_t s = (uint8_t)((stamp_head + 1) & 15);
        if (s == stamp_tail) return; /* sixteen lines waiting: this line end is lost with its stamp */
        line_stamp[stamp_head] = at;
        stamp_head = s;
    }
    rx_buf[rx_head] = b;
    rx_head = next;
}

ISR(USART_UDRE_vect)
{
    if (tx_tail == tx_head) {
        UCSR0B &= (uint8_t)~_BV(UDRIE0);
        return;
    }
    UDR0 = tx_buf[tx_tail];
    tx_tail = (uint8_t)((tx_tail + 1) & 127);
}

ISR(TIMER2_COMPA_vect) { ms++; }

/* Every pulse's falling edge: count it; the burst's last stops the clock and parks the pin low before the next
 * BOTTOM (within one period less the pulse: 128 cycles at 100 kHz). */
ISR(TIMER1_COMPA_vect)
{
    if (gate_pulse(&g)) {
        TCCR1B = _BV(WGM13) | _BV(WGM12);
        TCCR1A = _BV(WGM11);
    }
}

static void send_byte(uint8_t b)
{
    uint8_t next = (uint8_t)((tx_head + 1) & 127);
    while (next == tx_tail) {
        /* full: wait for the interrupt to make room (only a flood of refused lines gets here) */
    }
    tx_buf[tx_head] = b;
    tx_head = next;
    UCSR0B |= _BV(UDRIE0);
}

static void hal_send(const char *text)
{
    while (*text) send_byte((uint8_t)*text++);
    send_byte('\n');
}

/* The period the timer fires for hz, in CPU cycles, and the timer settings for it: the smallest prescaler whose tick
 * count fits 16 bits, chosen by comparing hz (no division), then one division for the tick count. */
static uint32_t fired_period_cycles(uint32_t hz, uint8_t *cs, uint16_t *ticks)
{
    uint8_t i = hz >= 245 ? 0 : hz >= 31 ? 1 : hz >= 4 ? 2 : 3;
    static const uint32_t per_tick[] = { F_CPU, F_CPU / 8, F_CPU / 64, F_CPU / 256 };
    static const uint8_t shift[] = { 0, 3, 6, 8 };
    uint32_t t = (per_tick[i] + hz / 2) / hz;
    *cs = (uint8_t)(i + 1); /* CS12:0 = 1, 2, 3, 4 for /1, /8, /64, /256 */
    *ticks = (uint16_t)(t - 1); /* ICR1 = TOP = ticks - 1 */
    return t << shift[i];
}

/* Timer1's settings for a scheduled train, computed when it is armed (its compare interrupt only writes them). Written
 * with the start disarmed and read by the interrupt after it is armed (cli/sei are the compiler's barriers). */
static uint16_t start_top, start_width;
static uint8_t start_cs, start_counted;
static volatile uint8_t armed;      /* a scheduled start waits for its compare match */
static volatile uint32_t start_at;  /* its time on the time base, START_TICKS early */

static void prepare(uint32_t hz, uint16_t *top, uint16_t *width, uint8_t *cs)
{
    fired_period_cycles(hz, cs, top);
    static const uint8_t shift[] = { 0, 0, 3, 6, 8 };
    uint16_t w = GATE_PULSE_CYCLES >> shift[*cs];
    if (w == 0) w = 1;
    *width = w - 1;
}

static inline __attribute__((always_inline)) void start_train(uint16_t top, uint16_t width, uint8_t cs, uint8_t counted)
{
    ICR1 = top;
    OCR1A = width;
    /* At TOP, so that the first timer tick wraps to BOTTOM and sets the output: the first pulse begins at once. */
    TCNT1 = top;
    if (counted) TIMSK1 = _BV(OCIE1A);
    TCCR1A = _BV(COM1A1) | _BV(WGM11);
    GTCCR = _BV(PSRSYNC); /* the prescaler starts afresh too, so the first tick is a whole one */
    TCCR1B = _BV(WGM13) | _BV(WGM12) | cs;
}

/* A scheduled start's compare match: OCR0A matches once every lap (128 us), so it starts the train only in its own lap.
 * The lap of the match: with an overflow pending the count has wrapped since, unless the match came before the wrap. */
ISR(TIMER0_COMPA_vect)
{
    uint8_t t = TCNT0;
    uint32_t laps = t0_laps;
    if ((TIFR0 & _BV(TOV0)) && t >= OCR0A) laps++;
    if (armed && (uint32_t)(laps << 8) == (start_at & 0xFFFFFF00UL)) {
        start_train(start_top, start_width, start_cs, start_counted);
        armed = 0;
        TIMSK0 = _BV(TOIE0);
    }
}

static void hal_fire(uint32_t hz, uint32_t pulses)
{
    /* Stop: clock off and OC1A disconnected, so the pin is PORTB1's low (a pulse under way is cut short); a scheduled
     * start still waiting is cancelled. */
    TCCR1B = _BV(WGM13) | _BV(WGM12);
    TCCR1A = _BV(WGM11);
    TIMSK1 = 0;
    TIFR1 = _BV(OCF1A) | _BV(TOV1);
    TIMSK0 = _BV(TOIE0);
    armed = 0;
#ifdef GATE_TRACE
    PINB = _BV(PB2); /* trace builds only: PB2 toggles when the train has been stopped (the twin's model is timed by it) */
#endif
    if (hz == 0) return;

    uint16_t top, width;
    uint8_t cs;
    prepare(hz, &top, &width, &cs);
    start_train(top, width, cs, pulses != 0);
}

/* The first pulse after_us after the line's last byte was received (its stamp, line_at): armed on Timer0's compare, or,
 * when that time is under ARM_MARGIN_TICKS away or past, started here (at once when past: the host asked too late). */
static void hal_fire_after(uint32_t hz, uint32_t pulses, uint32_t after_us)
{
    prepare(hz, &start_top, &start_width, &start_cs);
    start_counted = pulses != 0;
    uint32_t at = line_at + after_us * 2 - START_TICKS;
    cli();
    if ((int32_t)(at - now_ticks()) < ARM_MARGIN_TICKS) {
        while ((int32_t)(at - now_ticks()) > 0) {
        }
        start_train(start_top, start_width, start_cs, start_counted);
    } else {
        start_at = at;
        armed = 1;
        OCR0A = (uint8_t)at;
        TIFR0 = _BV(OCF0A);
        TIMSK0 = _BV(TOIE0) | _BV(OCIE0A);
    }
    sei();
}

static const gate_hal hal = { hal_fire, hal_send, hal_fire_after };

int main(void)
{
    PORTB &= (uint8_t)~_BV(PB1);
    DDRB |= _BV(PB1);
#ifdef GATE_TRACE
    DDRB |= _BV(PB2);
#endif

    UBRR0 = (F_CPU / 16 / 9600) - 1; /* 103 */
    UCSR0A = 0;
    UCSR0C = _BV(UCSZ01) | _BV(UCSZ00);
    UCSR0B = _BV(RXEN0) | _BV(TXEN0) | _BV(RXCIE0);

    TCCR2A = _BV(WGM21);
    OCR2A = 124;
    TIMSK2 = _BV(OCIE2A);
    TCCR2B = _BV(CS22) | _BV(CS20);

    TCCR0A = 0;
    TIMSK0 = _BV(TOIE0);
    TCCR0B = _BV(CS01); /* /8: 0.5 us a tick */

    set_sleep_mode(SLEEP_MODE_IDLE);
    gate_init(&g, &hal, GATE_FIRMWARE, GATE_WDOG_AT_POWER_UP);
    sei();

    for (;;) {
        cli();
        uint32_t now = ms;
        sei();
        gate_poll(&g, now);
        while (rx_tail != rx_head) {
            uint8_t b = rx_buf[rx_tail];
            rx_tail = (uint8_t)((rx_tail + 1) & 63);
            if (b == '\n') {
                cli();
                line_at = line_stamp[stamp_tail];
                stamp_tail = (uint8_t)((stamp_tail + 1) & 15);
                sei();
            }
            gate_byte(&g, b);
        }
        /* Idle until the next interrupt (a byte, the 1 ms tick, a pulse): the timers and the USART run on. sei then
         * sleep is atomic, so a byte that came in after the check still wakes the loop. */
        cli();
        if (rx_tail == rx_head) {
            sleep_enable();
            sei();
            sleep_cpu();
            sleep_disable();
        }
        sei();
    }
}
