/* The gate's portable core; see gate_core.h. Plain C99, no library calls, so that it builds for any chip. */
#include "gate_core.h"

enum { CMD_NONE, CMD_IDN, CMD_FREQ, CMD_OFF, CMD_STATE, CMD_PING, CMD_WDOG, CMD_BURST, CMD_BURST_AFTER, CMD_CAPS };

/* The command table: keyword and how many words follow it, in the twin's matching order. The scheduled burst is
 * BURST with four words, its third the literal AFTER (checked in execute). */
static const struct { const char *keyword; uint8_t args; uint8_t command; } commands[] = {
    { "*IDN?", 0, CMD_IDN },
    { "FREQ", 1, CMD_FREQ },
    { "OFF", 0, CMD_OFF },
    { "STATE?", 0, CMD_STATE },
    { "PING", 0, CMD_PING },
    { "WDOG", 1, CMD_WDOG },
    { "BURST", 2, CMD_BURST },
    { "BURST", 4, CMD_BURST_AFTER },
    { "CAPS?", 0, CMD_CAPS },
};
#define COMMAND_COUNT (sizeof commands / sizeof commands[0])

/* .NET's char.IsWhiteSpace over ASCII (the twin trims with it and its patterns split on \s). */
static uint8_t is_space(char c) { return c == ' ' || (c >= '\t' && c <= '\r'); }

static char upper(char c) { return (c >= 'a' && c <= 'z') ? (char)(c - 'a' + 'A') : c; }

static uint8_t same_word(const char *a, uint8_t len, const char *keyword)
{
    uint8_t i = 0;
    for (; i < len; i++) {
        if (keyword[i] == 0 || upper(a[i]) != keyword[i]) {
            return 0;
        }
    }
    return keyword[i] == 0;
}

uint8_t gate_parse_int(const char *s, uint8_t len, int32_t *value)
{
    uint8_t i = 0, negative = 0;
    uint32_t v = 0;
    if (len > 0 && (s[0] == '+' || s[0] == '-')) {
        negative = s[0] == '-';
        i = 1;
    }
    if (i == len) {
        return 0;
    }
    for (; i < len; i++) {
        if (s[i] < '0' || s[i] > '9') {
            return 0;
        }
        v = (v << 3) + (v << 1) + (uint32_t)(s[i] - '0'); /* x 10 without a multiply call on small chips */
        /* int32's range: 2147483647, or 2147483648 with a minus sign. */
        if (v > 2147483648UL || (v == 2147483648UL && !negative)) {
            return 0;
        }
    }
    *value = negative ? (int32_t)(0 - v) : (int32_t)v;
    return 1;
}

/* Appends text to a reply under construction. */
static char *put(char *at, const char *text)
{
    while (*text) {
        *at++ = *text++;
    }
    *at = 0;
    return at;
}

static char *put_u32(char *at, uint32_t v)
{
    char digits[10];
    uint8_t n = 0;
    do {
        digits[n++] = (char)('0' + v % 10);
        v /= 10;
    } while (v);
    while (n) {
        *at++ = digits[--n];
    }
    *at = 0;
    return at;
}

/* A burst that counted itself out is off (its interrupt says so; the main loop folds it in). */
static void fold_burst(gate *g)
{
    if (g->burst_done) {
        g->burst_done = 0;
        g->hz = 0;
    }
}

/* Any frequency command ends a burst under way, or one still waiting for its start: the train is stopped (and a
 * scheduled start cancelled) before the counter is set again. after_us: NO_AFTER to start at once. */
#define NO_AFTER 0xFFFFFFFFUL
static void set_frequency(gate *g, uint32_t hz, uint32_t pulses, uint32_t after_us)
{
    g->hal->fire(0, 0);
    g->burst_left = pulses;
    g->burst_done = 0;
    g->hz = hz;
    if (hz > 0) {
        if (after_us == NO_AFTER) {
            g->hal->fire(hz, pulses);
        } else {
            g->hal->fire_after(hz, pulses, after_us);
        }
    }
}

static void reply(gate *g, const char *a, uint32_t number, uint8_t with_number)
{
    char text[48];
    char *at = put(text, a);
    if (with_number) {
        put_u32(at, number);
    }
    g->hal->send(text);
}

static void execute(gate *g, const char *line, uint8_t len)
{
    /* Tokens: runs of non-space, as the twin's ^KEYWORD\s+(\S+)$ patterns see them. */
    const char *token[5];
    uint8_t token_len[5];
    uint8_t tokens = 0, too_many = 0;
    for (uint8_t i = 0; i < len;) {
        while (i < len && is_space(line[i])) i++;
        if (i == len) break;
        uint8_t start = i;
        while (i < len && !is_space(line[i])) i++;
        if (tokens < 5) {
            token[tokens] = line + start;
            token_len[tokens] = (uint8_t)(i - start);
            tokens++;
        } else {
            too_many = 1;
        }
    }

    uint8_t command = CMD_NONE;
    for (uint8_t c = 0; c < COMMAND_COUNT && !too_many; c++) {
        if (tokens == 1 + commands[c].args && same_word(token[0], token_len[0], commands[c].keyword)
            && (commands[c].command != CMD_BURST_AFTER || (g->hal->fire_after && same_word(token[3], token_len[3], "AFTER")))) {
            command = commands[c].command;
            break;
        }
    }

    if (command == CMD_NONE) {
        /* Known keyword, wrong arguments: the twin takes the keyword as the line up to its first space (only ' '). */
        uint8_t k = 0;
        while (k < len && line[k] != ' ') k++;
        for (uint8_t c = 0; c < COMMAND_COUNT; c++) {
            if (same_word(line, k, commands[c].keyword)) {
                reply(g, "ERR 3 SYNTAX", 0, 0);
                return;
            }
        }
        reply(g, "ERR 1 UNKNOWN", 0, 0);
        return;
    }

    int32_t a = 0, b = 0, c = 0;
    if ((tokens >= 2 && !gate_parse_int(token[1], token_len[1], &a))
        || (tokens >= 3 && !gate_parse_int(token[2], token_len[2], &b))
        || (tokens >= 5 && !gate_parse_int(token[4], token_len[4], &c))) {
        reply(g, "ERR 3 SYNTAX", 0, 0);
        return;
    }

    switch (command) {
    case CMD_IDN: {
        char text[48];
        put(put(text, "OK PICGATE "), g->firmware);
        g->hal->send(text);
        return;
    }
    case CMD_FREQ:
        if (a < 0 || (uint32_t)a > GATE_MAX_HZ) break;
        set_frequency(g, (uint32_t)a, 0, NO_AFTER);
        reply(g, "OK FREQ ", (uint32_t)a, 1);
        return;
    case CMD_OFF:
        set_frequency(g, 0, 0, NO_AFTER);
        reply(g, "OK FREQ 0", 0, 0);
        return;
    case CMD_STATE: {
        char text[48];
        char *at = put_u32(put(text, "OK STATE "), g->hz);
        at = put(at, g->hz > 0 ? " ON WDOG " : " OFF WDOG ");
        at = put_u32(at, g->wdog_ms);
        if (g->tripped) {
            put(at, " TRIPPED");
        }
        g->tripped = 0;
        g->hal->send(text);
        return;
    }
    case CMD_PING:
        reply(g, "OK PONG", 0, 0);
        return;
    case CMD_WDOG:
        if (a != 0 && (a < (int32_t)GATE_MIN_WDOG_MS || a > (int32_t)GATE_MAX_WDOG_MS)) break;
        g->wdog_ms = (uint32_t)a;
        reply(g, "OK WDOG ", (uint32_t)a, 1);
        return;
    case CMD_BURST:
        if (a < 1 || (uint32_t)a > GATE_MAX_BURST || b < 1 || (uint32_t)b > GATE_MAX_HZ) break;
        set_frequency(g, (uint32_t)b, (uint32_t)a, NO_AFTER);
        reply(g, "OK BURST ", (uint32_t)a, 1);
        return;
    case CMD_BURST_AFTER: {
        if (a < 1 || (uint32_t)a > GATE_MAX_BURST || b < 1 || (uint32_t)b > GATE_MAX_HZ || c < 0 || (uint32_t)c > GATE_MAX_AFTER_US) break;
        /* Armed at once (the reply says it was accepted); the HAL's timer fires the first pulse c us after the line's
         * last byte. Waiting counts as firing: STATE? says ON and the watchdog watches the wait. */
        set_frequency(g, (uint32_t)b, (uint32_t)a, (uint32_t)c);
        char text[48];
        put_u32(put(put_u32(put(text, "OK BURST "), (uint32_t)a), " AFTER "), (uint32_t)c);
        g->hal->send(text);
        return;
    }
    case CMD_CAPS:
        /* What this gate can do beyond the base protocol; an older gate answers CAPS? with ERR 1 UNKNOWN. */
        reply(g, g->hal->fire_after ? "OK CAPS AFTER" : "OK CAPS", 0, 0);
        return;
    }
    reply(g, "ERR 2 RANGE", 0, 0);
}

void gate_init(gate *g, const gate_hal *hal, const char *firmware, uint32_t wdog_ms)
{
    g->hal = hal;
    g->firmware = firmware;
    g->len = 0;
    g->overflow = 0;
    g->hz = 0;
    g->wdog_ms = wdog_ms;
    g->last_heard_ms = 0;
    g->now_ms = 0;
    g->tripped = 0;
    g->trips = 0;
    g->burst_left = 0;
    g->burst_done = 0;
    hal->fire(0, 0);
}

void gate_byte(gate *g, uint8_t b)
{
    if (b != '\n') {
        if (g->len < GATE_LINE_MAX) {
            /* The twin decodes the line as ASCII, which reads every byte above 0x7F as '?'. */
            g->line[g->len++] = b >= 0x80 ? '?' : (char)b;
        } else {
            g->overflow = 1;
        }
        return;
    }

    /* Every line heard, valid or not, empty or not, feeds the watchdog. */
    g->last_heard_ms = g->now_ms;
    fold_burst(g);
    uint8_t len = g->len, overflow = g->overflow;
    g->len = 0;
    g->overflow = 0;
    if (overflow) {
        reply(g, "ERR 1 UNKNOWN", 0, 0);
        return;
    }
    const char *line = g->line;
    while (len > 0 && is_space(line[len - 1])) len--;
    while (len > 0 && is_space(line[0])) { line++; len--; }
    if (len > 0) {
        execute(g, line, len);
    }
}

void gate_poll(gate *g, uint32_t now_ms)
{
    g->now_ms = now_ms;
    fold_burst(g);
    /* Off when no line was heard for the whole watchdog time: at the first count past it, so never early and at most
     * one count (1 ms) late. */
    if (g->hz > 0 && g->wdog_ms > 0 && (uint32_t)(now_ms - g->last_heard_ms) > g->wdog_ms) {
        set_frequency(g, 0, 0, NO_AFTER);
        g->tripped = 1;
        g->trips++;
    }
}
