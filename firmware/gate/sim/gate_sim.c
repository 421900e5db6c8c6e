/* Runs the gate's AVR image in simavr, cycle by cycle, and reports what the gate did (make -C firmware/gate test-avr).
 *
 *   gate_sim FIRMWARE.elf SCRIPT
 *
 * SCRIPT, one item a line ('#' starts a comment):
 *   CYCLE TEXT     a line whose last byte has arrived (its RXC raised, the end of its stop bit in simavr's UART) at
 *                  CYCLE; the harness adds '\n'. Escapes in TEXT: \r, \t, \\, \xHH. Its bytes are put into the UART one
 *                  simavr byte time apart, ending there.
 *   end CYCLE      run until CYCLE, then report and stop.
 * Output, one event a line, in cycle order within each kind:
 *   edge CYCLE 0|1     every change of the pulse pin PB1 / OC1A (Arduino D9)
 *   reply CYCLE TEXT   a reply line; CYCLE is when its '\n' was handed to the UART plus one byte time (its last stop bit)
 *   sent CYCLE TEXT    echo of each scripted line, with the cycle its last byte arrived
 *   trace CYCLE 0|1    a trace build's PB2 (toggled when the firmware has stopped the train)
 *   byte_cycles N      simavr's UART byte time in cycles (it counts a parity bit even with none: 11 bits)
 * Everything is in simulated cycles at 16 MHz: no wall clock, so the run is the same every time. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sim_avr.h>
#include <sim_elf.h>
#include <sim_irq.h>
#include <sim_cycle_timers.h>
#include <avr_uart.h>
#include <avr_ioport.h>

/* UBRR 103 at 16 MHz: 1664 cycles a bit; simavr 1.6's UART counts 1 start + 8 data + 1 parity + 1 stop. */
#define BIT_CYCLES 1664
static avr_cycle_count_t byte_cycles = BIT_CYCLES * 11;

typedef struct { avr_cycle_count_t at; uint8_t b; } inject_t;
static inject_t *injects;
static size_t inject_count, inject_next, inject_cap;
static avr_irq_t *uart_in;
static char reply[256];
static size_t reply_len;

static void add_inject(avr_cycle_count_t at, uint8_t b)
{
    if (inject_count == inject_cap) {
        inject_cap = inject_cap ? inject_cap * 2 : 256;
        injects = realloc(injects, inject_cap * sizeof *injects);
    }
    injects[inject_count].at = at;
    injects[inject_count].b = b;
    inject_count++;
}

static int by_cycle(const void *a, const void *b)
{
    const inject_t *x = a, *y = b;
    return x->at < y->at ? -1 : x->at > y->at ? 1 : 0;
}

static avr_cycle_count_t inject_due(avr_t *avr, avr_cycle_count_t when, void *param)
{
    (void)param;
    while (inject_next < inject_count && injects[inject_next].at <= when) {
        avr_raise_irq(uart_in, injects[inject_next].b);
        inject_next++;
    }
    (void)avr;
    return inject_next < inject_count ? injects[inject_next].at : 0;
}

static void on_pin(avr_irq_t *irq, uint32_t value, void *param)
{
    avr_t *avr = param;
    (void)irq;
    printf("edge %llu %u\n", (unsigned long long)avr->cycle, value ? 1u : 0u);
}

static void on_trace(avr_irq_t *irq, uint32_t value, void *param)
{
    avr_t *avr = param;
    (void)irq;
    printf("trace %llu %u\n", (unsigned long long)avr->cycle, value ? 1u : 0u);
}

static void on_uart_out(avr_irq_t *irq, uint32_t value, void *param)
{
    avr_t *avr = param;
    (void)irq;
    uint8_t b = (uint8_t)value;
    if (b == '\n') {
        reply[reply_len] = 0;
        printf("reply %llu %s\n", (unsigned long long)(avr->cycle + byte_cycles), reply);
        reply_len = 0;
    } else if (reply_len < sizeof reply - 1) {
        reply[reply_len++] = (char)b;
    }
}

static size_t unescape(const char *s, uint8_t *out)
{
    size_t n = 0;
    while (*s) {
        if (s[0] == '\\' && s[1] == 'r') { out[n++] = '\r'; s += 2; }
        else if (s[0] == '\\' && s[1] == 't') { out[n++] = '\t'; s += 2; }
        else if (s[0] == '\\' && s[1] == '\\') { out[n++] = '\\'; s += 2; }
        else if (s[0] == '\\' && s[1] == 'x' && s[2] && s[3]) {
            char hex[3] = { s[2], s[3], 0 };
            out[n++] = (uint8_t)strtoul(hex, NULL, 16);
            s += 4;
        } else out[n++] = (uint8_t)*s++;
    }
    return n;
}

static void no_sleep(avr_t *avr, avr_cycle_count_t how_long) { (void)avr; (void)how_long; }

int main(int argc, char **argv)
{
    if (argc != 3) {
        fprintf(stderr, "usage: gate_sim FIRMWARE.elf SCRIPT\n");
        return 2;
    }
    elf_firmware_t fw;
    memset(&fw, 0, sizeof fw);
    if (elf_read_firmware(argv[1], &fw) != 0) {
        fprintf(stderr, "%s: not a firmware image simavr can read\n", argv[1]);
        return 2;
    }
    avr_t *avr = avr_make_mcu_by_name("atmega328p");
    if (!avr) return 2;
    avr_init(avr);
    avr->frequency = 16000000;
    /* simavr's default sleep waits the sleep's time on the wall clock; here only cycles count, so a sleep costs nothing. */
    avr->sleep = no_sleep;
    avr->log = LOG_ERROR;
    avr_load_firmware(avr, &fw);

    uint32_t flags = 0;
    avr_ioctl(avr, AVR_IOCTL_UART_GET_FLAGS('0'), &flags);
    flags &= ~(uint32_t)(AVR_UART_FLAG_STDIO | AVR_UART_FLAG_POLL_SLEEP);
    avr_ioctl(avr, AVR_IOCTL_UART_SET_FLAGS('0'), &flags);
    uart_in = avr_io_getirq(avr, AVR_IOCTL_UART_GETIRQ('0'), UART_IRQ_INPUT);
    avr_irq_register_notify(avr_io_getirq(avr, AVR_IOCTL_UART_GETIRQ('0'), UART_IRQ_OUTPUT), on_uart_out, avr);
    avr_irq_register_notify(avr_io_getirq(avr, AVR_IOCTL_IOPORT_GETIRQ('B'), 1), on_pin, avr);
    /* A trace build (-DGATE_TRACE) toggles PB2 when it has stopped the train. */
    avr_irq_register_notify(avr_io_getirq(avr, AVR_IOCTL_IOPORT_GETIRQ('B'), 2), on_trace, avr);

    FILE *script = fopen(argv[2], "r");
    if (!script) {
        fprintf(stderr, "%s: cannot read the script\n", argv[2]);
        return 2;
    }
    char text[4096];
    uint8_t bytes[4096];
    avr_cycle_count_t end = 0;
    printf("byte_cycles %llu\n", (unsigned long long)byte_cycles);
    while (fgets(text, sizeof text, script)) {
        text[strcspn(text, "\n")] = 0;
        if (text[0] == '#' || text[0] == 0) continue;
        if (strncmp(text, "end ", 4) == 0) {
            end = strtoull(text + 4, NULL, 10);
            continue;
        }
        char *rest;
        avr_cycle_count_t at = strtoull(text, &rest, 10);
        if (*rest == ' ') rest++;
        size_t n = unescape(rest, bytes);
        bytes[n++] = '\n';
        /* simavr raises RXC one byte time after a byte goes in, and the next one byte time later while more wait. */
        for (size_t i = 0; i < n; i++) add_inject(at - (n - i) * byte_cycles, bytes[i]);
        printf("sent %llu %s\n", (unsigned long long)at, rest);
    }
    fclose(script);
    qsort(injects, inject_count, sizeof *injects, by_cycle);
    if (inject_count) avr_cycle_timer_register(avr, injects[0].at, inject_due, NULL);

    while (avr->cycle < end) {
        int state = avr_run(avr);
        if (state == cpu_Done || state == cpu_Crashed) {
            fprintf(stderr, "the simulated gate stopped (state %d) at cycle %llu\n", state, (unsigned long long)avr->cycle);
            return 1;
        }
    }
    printf("end %llu\n", (unsigned long long)avr->cycle);
    return 0;
}
