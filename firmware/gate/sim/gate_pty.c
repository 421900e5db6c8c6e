/* The AVR gate image in simavr on the wall clock, its UART on a pseudo-terminal, for a host in another process
 * (laserengrave laser, machine check, engrave with laserengrave simulator for the stages):
 *
 *   gate_pty FIRMWARE.elf [EDGES_OUT [LINES_OUT [LINK]]]      (- for an output not wanted)
 *
 * simavr's uart_pty makes the pty and links it as /tmp/simavr-uart0 (printed at start); the host opens that path as
 * its gate port, or LINK when given (a link of its own, so that two of these can run side by side). Every line the
 * gate received goes to LINES_OUT as "CYCLE TEXT", CYCLE being its last byte's receive-complete (RXC) in simavr: the
 * same instant sim/gate_sim.c's scripts give, so the recorded stream can be replayed there and in the twin. The simulated CPU is held to the wall clock (16 MHz of cycles a second), so the watchdog and the
 * pulse train take their real time. Every edge of the pulse pin PB1 goes to EDGES_OUT ("CYCLE 0|1" a line) when given,
 * and each train's pulse count to stderr as it ends. Runs until killed (SIGINT/SIGTERM). */
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>
#include <sim_avr.h>
#include <sim_elf.h>
#include <sim_irq.h>
#include <avr_ioport.h>
#include <avr_uart.h>
#include <sim_interrupts.h>
#include <parts/uart_pty.h>

static volatile sig_atomic_t stop;
static FILE *edges;
static unsigned long train, trains;
static avr_cycle_count_t last_rise;

/* The bytes given to the UART, in order; each RXC interrupt raised is the next of them received. */
static FILE *lines;
static unsigned char queued[4096];
static unsigned q_head, q_tail;
static char line[256];
static unsigned line_len;

static void on_input(avr_irq_t *irq, uint32_t value, void *param)
{
    (void)irq; (void)param;
    queued[q_tail++ % sizeof queued] = (unsigned char)value;
}

static void on_rxc(avr_irq_t *irq, uint32_t value, void *param)
{
    avr_t *avr = param;
    (void)irq;
    if (!value || q_head == q_tail) return;
    unsigned char b = queued[q_head++ % sizeof queued];
    if (b == '\n') {
        while (line_len && line[line_len - 1] == '\r') line_len--;
        line[line_len] = 0;
        fprintf(lines, "%llu %s\n", (unsigned long long)avr->cycle, line);
        fflush(lines);
        line_len = 0;
    } else if (line_len < sizeof line - 1) {
        line[line_len++] = (char)b;
    }
}

static void on_signal(int s) { (void)s; stop = 1; }

static void on_pin(avr_irq_t *irq, uint32_t value, void *param)
{
    avr_t *avr = param;
    (void)irq;
    if (edges) {
        fprintf(edges, "%llu %u\n", (unsigned long long)avr->cycle, value ? 1u : 0u);
        fflush(edges);
    }
    if (value) {
        /* A new train when the gap is longer than one period of the slowest frequency (1 Hz) could be: 1.5 s. */
        if (train && avr->cycle - last_rise > 24000000ULL) {
            fprintf(stderr, "train %lu: %lu pulses\n", ++trains, train);
            train = 0;
        }
        train++;
        last_rise = avr->cycle;
    }
}

static double now_s(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return t.tv_sec + t.tv_nsec / 1e9;
}

static void no_sleep(avr_t *avr, avr_cycle_count_t how_long) { (void)avr; (void)how_long; }

int main(int argc, char **argv)
{
    if (argc < 2) {
        fprintf(stderr, "usage: gate_pty FIRMWARE.elf [EDGES_OUT [LINES_OUT [LINK]]]\n");
        return 2;
    }
    elf_firmware_t fw;
    memset(&fw, 0, sizeof fw);
    if (elf_read_firmware(argv[1], &fw) != 0) return 2;
    avr_t *avr = avr_make_mcu_by_name("atmega328p");
    if (!avr) return 2;
    avr_init(avr);
    avr->frequency = 16000000;
    /* simavr's default sleep waits the sleep's time on the wall clock on top of this loop's own pacing, so the chip fell
     * behind by up to a sleep's length; the loop below alone holds it to the wall clock. */
    avr->sleep = no_sleep;
    avr->log = LOG_ERROR;
    avr_load_firmware(avr, &fw);
    if (argc > 2 && strcmp(argv[2], "-") != 0) edges = fopen(argv[2], "w");
    if (argc > 3 && strcmp(argv[3], "-") != 0) lines = fopen(argv[3], "w");
    const char *link = argc > 4 ? argv[4] : NULL;
    avr_irq_register_notify(avr_io_getirq(avr, AVR_IOCTL_IOPORT_GETIRQ('B'), 1), on_pin, avr);

    static uart_pty_t pty;
    uart_pty_init(avr, &pty);
    uart_pty_connect(&pty, '0');
    if (lines) {
        /* The host's bytes as they enter the UART, and the receive-complete interrupt of each (raised to 1 when queued). */
        avr_irq_register_notify(avr_io_getirq(avr, AVR_IOCTL_UART_GETIRQ('0'), UART_IRQ_INPUT), on_input, avr);
        avr_irq_register_notify(avr_get_interrupt_irq(avr, 18 /* USART_RX_vect */) + AVR_INT_IRQ_PENDING, on_rxc, avr);
    }
    if (link) {
        unlink(link);
        if (symlink(pty.port[0].slavename, link) != 0) {
            perror(link);
            return 2;
        }
    }
    fprintf(stderr, "gate on %s (%s)\n", pty.port[0].slavename, link ? link : "/tmp/simavr-uart0");
    signal(SIGINT, on_signal);
    signal(SIGTERM, on_signal);

    double start = now_s(), worst_lag = 0;
    while (!stop) {
        avr_cycle_count_t due = (avr_cycle_count_t)((now_s() - start) * 16e6);
        /* How far the simulated chip has fallen behind the wall clock (a real chip never does): the host sees its
         * replies that much late. Reported at exit, as a run's explanation when a reply was late. */
        double lag = (double)(due - avr->cycle) / 16e6;
        if (due > avr->cycle && lag > worst_lag) worst_lag = lag;
        while (avr->cycle < due && !stop) {
            int state = avr_run(avr);
            if (state == cpu_Done || state == cpu_Crashed) {
                fprintf(stderr, "the simulated gate stopped (state %d)\n", state);
                return 1;
            }
        }
        usleep(200);
    }
    if (train) fprintf(stderr, "train %lu: %lu pulses\n", ++trains, train);
    fprintf(stderr, "the simulated gate fell behind the wall clock by at most %.1f ms\n", worst_lag * 1e3);
    if (edges) fclose(edges);
    if (lines) fclose(lines);
    if (link) unlink(link);
    /* Not uart_pty_stop: it waits for its reader thread, which can sit in a read of the pty for good. */
    unlink("/tmp/simavr-uart0");
    return 0;
}
