/* Unit tests of the gate's portable core, compiled natively (make -C firmware/gate test-core).
 * A fake HAL records what the core asked of the hardware; pulses and milliseconds are stepped by the test. */
#include <stdio.h>
#include <string.h>
#include "../core/gate_core.h"

static char replies[16][64];
static int reply_count;
static uint32_t fired_hz, fired_pulses, fire_calls;
static uint32_t fired_after; /* the delay of the last scheduled start; NO_AFTER_SEEN when the last fire started at once */
#define NO_AFTER_SEEN 0xFFFFFFFFUL
static int passed, failed;

static void fake_fire(uint32_t hz, uint32_t pulses) { fired_hz = hz; fired_pulses = pulses; fired_after = NO_AFTER_SEEN; fire_calls++; }
static void fake_fire_after(uint32_t hz, uint32_t pulses, uint32_t after_us)
{
    fired_hz = hz;
    fired_pulses = pulses;
    fired_after = after_us;
    fire_calls++;
}
static void fake_send(const char *text)
{
    if (reply_count < 16) {
        strncpy(replies[reply_count], text, 63);
    }
    reply_count++;
}
static const gate_hal hal = { fake_fire, fake_send, fake_fire_after };
static const gate_hal hal_without_after = { fake_fire, fake_send, 0 };
static gate g;

static void reset(void)
{
    reply_count = 0;
    fire_calls = 0;
    gate_init(&g, &hal, "TEST-1", 1000);
}

static void feed(const char *bytes, size_t n) { for (size_t i = 0; i < n; i++) gate_byte(&g, (uint8_t)bytes[i]); }
static void send_line(const char *s) { feed(s, strlen(s)); gate_byte(&g, '\n'); }

/* Sends one line and returns its only reply ("" when none, "<n replies>" when more than one). */
static const char *ask(const char *s)
{
    reply_count = 0;
    send_line(s);
    if (reply_count == 0) return "";
    if (reply_count > 1) return "<more than one reply>";
    return replies[0];
}

static void check(int ok, const char *name, const char *detail)
{
    if (ok) { passed++; }
    else { failed++; printf("FAIL %s: %s\n", name, detail); }
}

static void expect(const char *name, const char *line, const char *want)
{
    const char *got = ask(line);
    char detail[256];
    snprintf(detail, sizeof detail, "'%s' answered '%s', expected '%s'", line, got, want);
    check(strcmp(got, want) == 0, name, detail);
}

static void expect_u32(const char *name, uint32_t got, uint32_t want)
{
    char detail[128];
    snprintf(detail, sizeof detail, "got %lu, expected %lu", (unsigned long)got, (unsigned long)want);
    check(got == want, name, detail);
}

/* Runs the fake's pulse interrupt until the core says stop (or limit pulses); returns the pulses fired. */
static uint32_t run_pulses(uint32_t limit)
{
    uint32_t n = 0;
    while (n < limit && fired_hz > 0) {
        n++;
        if (gate_pulse(&g)) { fired_hz = 0; break; }
    }
    return n;
}

static void commands_answer_as_the_protocol_says(void)
{
    reset();
    expect("Identify_Asked_NamesFirmware", "*IDN?", "OK PICGATE TEST-1");
    expect("Identify_LowerCase_Answers", "*idn?", "OK PICGATE TEST-1");
    expect("Freq_InRange_Acknowledged", "FREQ 1000", "OK FREQ 1000");
    expect_u32("Freq_InRange_FiresAtThatFrequency", fired_hz, 1000);
    expect_u32("Freq_InRange_FiresUntilTold", fired_pulses, 0);
    expect("State_Firing_SaysOn", "STATE?", "OK STATE 1000 ON WDOG 1000");
    expect("Freq_Zero_Acknowledged", "FREQ 0", "OK FREQ 0");
    expect_u32("Freq_Zero_Stops", fired_hz, 0);
    expect("State_Off_SaysOff", "STATE?", "OK STATE 0 OFF WDOG 1000");
    expect("Freq_Max_Acknowledged", "FREQ 100000", "OK FREQ 100000");
    expect("Off_Firing_AcknowledgedAsFreq0", "OFF", "OK FREQ 0");
    expect_u32("Off_Firing_Stops", fired_hz, 0);
    expect("Ping_Any_Pongs", "PING", "OK PONG");
    expect("Wdog_Zero_Disables", "WDOG 0", "OK WDOG 0");
    expect("Wdog_Min_Acknowledged", "WDOG 50", "OK WDOG 50");
    expect("Wdog_Max_Acknowledged", "WDOG 60000", "OK WDOG 60000");
    expect("State_AfterWdog_ReportsIt", "STATE?", "OK STATE 0 OFF WDOG 60000");
    expect("Burst_InRange_AcknowledgesCount", "BURST 5 1000", "OK BURST 5");
    expect_u32("Burst_InRange_FiresCounted", fired_pulses, 5);
    expect("Burst_Max_Acknowledged", "BURST 1000000 100000", "OK BURST 1000000");
    expect("Freq_PlusSignAndZeros_ReadAsNumber", "FREQ +0005", "OK FREQ 5");
    expect("Freq_MinusZero_IsZero", "FREQ -0", "OK FREQ 0");
    expect("Freq_TabsAndSpaces_Accepted", " \tfreq \t 20 \t", "OK FREQ 20");
    expect("Freq_CrLf_Accepted", "FREQ 30\r", "OK FREQ 30");
}

static void errors_answer_as_the_protocol_says(void)
{
    reset();
    expect("Unknown_Word_Err1", "FIRE", "ERR 1 UNKNOWN");
    expect("Unknown_KeywordPrefix_Err1", "FREQX 5", "ERR 1 UNKNOWN");
    expect("Unknown_KeywordGluedByTab_Err1", "FREQ\t5 6", "ERR 1 UNKNOWN");
    expect("Freq_Above100k_Err2", "FREQ 100001", "ERR 2 RANGE");
    expect("Freq_Negative_Err2", "FREQ -1", "ERR 2 RANGE");
    expect("Freq_NotANumber_Err3", "FREQ abc", "ERR 3 SYNTAX");
    expect("Freq_Decimal_Err3", "FREQ 1.5", "ERR 3 SYNTAX");
    expect("Freq_NoArgument_Err3", "FREQ", "ERR 3 SYNTAX");
    expect("Freq_TwoArguments_Err3", "FREQ 1 2", "ERR 3 SYNTAX");
    expect("Freq_SignOnly_Err3", "FREQ +", "ERR 3 SYNTAX");
    expect("Freq_BeyondInt32_Err3", "FREQ 2147483648", "ERR 3 SYNTAX");
    expect("Freq_Int32Max_Err2", "FREQ 2147483647", "ERR 2 RANGE");
    expect("Freq_Int32Min_Err2", "FREQ -2147483648", "ERR 2 RANGE");
    expect("Off_WithArgument_Err3", "OFF 3", "ERR 3 SYNTAX");
    expect("Ping_WithArgument_Err3", "ping x", "ERR 3 SYNTAX");
    expect("Identify_WithArgument_Err3", "*IDN? now", "ERR 3 SYNTAX");
    expect("Wdog_Below50_Err2", "WDOG 49", "ERR 2 RANGE");
    expect("Wdog_Above60000_Err2", "WDOG 60001", "ERR 2 RANGE");
    expect("Wdog_NotANumber_Err3", "WDOG x", "ERR 3 SYNTAX");
    expect("Burst_ZeroPulses_Err2", "BURST 0 1000", "ERR 2 RANGE");
    expect("Burst_TooManyPulses_Err2", "BURST 1000001 1000", "ERR 2 RANGE");
    expect("Burst_ZeroHz_Err2", "BURST 5 0", "ERR 2 RANGE");
    expect("Burst_Above100k_Err2", "BURST 5 100001", "ERR 2 RANGE");
    expect("Burst_SecondNotANumber_Err3", "BURST 5 x", "ERR 3 SYNTAX");
    expect("Burst_OneArgument_Err3", "BURST 5", "ERR 3 SYNTAX");
    expect("Burst_FiveTokens_Err3", "BURST 1 2 3 4", "ERR 3 SYNTAX");
    expect_u32("Errors_Any_NeverFired", fired_hz, 0);
    expect("Empty_Line_NoReply", "", "");
    expect("Blank_Line_NoReply", " \r", "");

    /* A refusal changes nothing: the laser fires on. */
    ask("FREQ 1000");
    ask("FREQ 200000");
    expect_u32("Freq_RefusedWhileFiring_KeepsFiring", fired_hz, 1000);
    expect("State_AfterRefusal_Unchanged", "STATE?", "OK STATE 1000 ON WDOG 1000");
}

static void bursts_count_exactly(void)
{
    reset();
    ask("BURST 7 1000");
    uint32_t n = run_pulses(100);
    expect_u32("Burst_Seven_FiresSeven", n, 7);
    gate_poll(&g, 0);
    expect("Burst_Ended_StateOff", "STATE?", "OK STATE 0 OFF WDOG 1000");

    ask("BURST 1 100000");
    expect_u32("Burst_One_FiresOne", run_pulses(100), 1);

    ask("BURST 1000000 100000");
    expect_u32("Burst_Million_FiresMillion", run_pulses(2000000), 1000000);

    /* STATE? right after the count ended, before the main loop polled: already off. */
    ask("BURST 3 500");
    run_pulses(100);
    expect("Burst_EndedNotYetPolled_StateOff", "STATE?", "OK STATE 0 OFF WDOG 1000");
}

static void later_command_ends_burst(void)
{
    reset();
    ask("BURST 10 1000");
    expect_u32("Burst_ThenFreq_FirstPulses", run_pulses(4), 4);
    expect("Burst_ThenFreq_Acknowledged", "FREQ 2000", "OK FREQ 2000");
    expect_u32("Burst_ThenFreq_FiresUncounted", fired_pulses, 0);
    expect_u32("Burst_ThenFreq_NotStoppedByOldCount", run_pulses(50), 50);

    ask("BURST 10 1000");
    run_pulses(4);
    ask("OFF");
    expect_u32("Burst_ThenOff_Stopped", fired_hz, 0);
    expect("Burst_ThenOff_StateOff", "STATE?", "OK STATE 0 OFF WDOG 1000");

    ask("BURST 10 1000");
    run_pulses(4);
    ask("BURST 3 2000");
    expect_u32("Burst_ThenBurst_NewCount", run_pulses(50), 3);

    /* PING and STATE? are not frequency commands: the burst goes on and its count holds. */
    ask("BURST 10 1000");
    run_pulses(4);
    ask("PING");
    ask("STATE?");
    expect_u32("Burst_ThenPing_CountHolds", run_pulses(50), 6);
}

static void watchdog_switches_off_after_silence(void)
{
    reset();
    gate_poll(&g, 100);
    ask("FREQ 1000");                 /* heard at 100 ms */
    gate_poll(&g, 1100);
    expect_u32("Watchdog_AtExactlyItsTime_StillFiring", fired_hz, 1000);
    gate_poll(&g, 1101);
    expect_u32("Watchdog_OneMsPastItsTime_Off", fired_hz, 0);
    expect("Watchdog_Tripped_StateSaysTripped", "STATE?", "OK STATE 0 OFF WDOG 1000 TRIPPED");
    expect("Watchdog_TrippedReported_ClearedAfterState", "STATE?", "OK STATE 0 OFF WDOG 1000");

    /* Any line feeds it, even an unknown or empty one. */
    gate_poll(&g, 2000);
    ask("FREQ 1000");
    gate_poll(&g, 2900);
    ask("NONSENSE");
    gate_poll(&g, 3800);
    ask("");
    gate_poll(&g, 4700);
    expect_u32("Watchdog_FedByAnyLine_StillFiring", fired_hz, 1000);
    gate_poll(&g, 4801);
    expect_u32("Watchdog_FedByAnyLine_OffAfterLastLine", fired_hz, 0);

    /* Disabled: fires on. */
    ask("WDOG 0");
    ask("FREQ 1000");
    gate_poll(&g, 4801 + 100000);
    expect_u32("Watchdog_Disabled_FiresOn", fired_hz, 1000);

    /* WDOG 50 times from the last line heard. */
    ask("WDOG 50");                    /* heard at 104801 */
    gate_poll(&g, 104851);
    expect_u32("Watchdog_50ms_NotBefore", fired_hz, 1000);
    gate_poll(&g, 104852);
    expect_u32("Watchdog_50ms_Off", fired_hz, 0);

    /* A burst is watched too; not firing, nothing trips. */
    ask("STATE?");
    ask("BURST 1000 1000");            /* heard at 104852 */
    gate_poll(&g, 104903);
    expect_u32("Watchdog_DuringBurst_Off", fired_hz, 0);
    expect("Watchdog_DuringBurst_Tripped", "STATE?", "OK STATE 0 OFF WDOG 50 TRIPPED");
    gate_poll(&g, 200000);
    expect("Watchdog_NotFiring_NeverTrips", "STATE?", "OK STATE 0 OFF WDOG 50");

    /* The millisecond count wraps around. */
    reset();
    gate_poll(&g, 0xFFFFFF00UL);
    ask("FREQ 10");
    gate_poll(&g, (uint32_t)(0xFFFFFF00UL + 1000));
    expect_u32("Watchdog_CountWraps_NotEarly", fired_hz, 10);
    gate_poll(&g, (uint32_t)(0xFFFFFF00UL + 1001));
    expect_u32("Watchdog_CountWraps_Off", fired_hz, 0);
}

static void lines_split_long_and_not_ascii(void)
{
    reset();
    reply_count = 0;
    feed("FR", 2);
    feed("EQ 1", 4);
    check(reply_count == 0, "Split_BeforeLineEnd_NoReply", "a reply before the line ended");
    feed("23", 2);
    feed("\n", 1);
    check(reply_count == 1 && strcmp(replies[0], "OK FREQ 123") == 0, "Split_AcrossReads_OneCommand", replies[0]);

    reply_count = 0;
    feed("PING\nSTATE?\r\nOFF\n", 17);
    check(reply_count == 3 && strcmp(replies[0], "OK PONG") == 0 && strcmp(replies[1], "OK STATE 123 ON WDOG 1000") == 0
          && strcmp(replies[2], "OK FREQ 0") == 0, "Lines_ThreeInOneRead_ThreeReplies", replies[1]);

    char longline[200];
    memset(longline, ' ', sizeof longline);
    memcpy(longline, "PING", 4);
    longline[128] = 0;                  /* 128 bytes: kept, trailing spaces trimmed */
    expect("Line_128Bytes_Kept", longline, "OK PONG");
    longline[128] = ' ';
    longline[129] = 0;                  /* 129 bytes: too long */
    expect("Line_129Bytes_Unknown", longline, "ERR 1 UNKNOWN");
    expect("Line_AfterOverLong_ParsedAfresh", "PING", "OK PONG");
    char huge[1000];
    memset(huge, 'A', sizeof huge - 1);
    huge[sizeof huge - 1] = 0;
    expect("Line_1000Bytes_OneUnknown", huge, "ERR 1 UNKNOWN");

    expect("NotAscii_Word_Unknown", "P\xC3\xAFNG", "ERR 1 UNKNOWN");
    expect("NotAscii_InNumber_Syntax", "FREQ 1\xff" "0", "ERR 3 SYNTAX");
    expect("NotAscii_AfterCommand_Syntax", "PING \x80", "ERR 3 SYNTAX");
    reply_count = 0;
    feed("PI\0NG\n", 6);
    check(reply_count == 1 && strcmp(replies[0], "ERR 1 UNKNOWN") == 0, "Nul_InWord_Unknown", replies[0]);
    expect_u32("NotAscii_Any_NeverFired", fired_hz, 0);
}

static void numbers_parse_as_dotnet_does(void)
{
    int32_t v = 0;
    check(gate_parse_int("2147483647", 10, &v) && v == 2147483647, "ParseInt_Int32Max_Parsed", "");
    check(gate_parse_int("-2147483648", 11, &v) && v == (int32_t)0x80000000, "ParseInt_Int32Min_Parsed", "");
    check(!gate_parse_int("2147483648", 10, &v), "ParseInt_AboveInt32_Refused", "");
    check(!gate_parse_int("99999999999999999999", 20, &v), "ParseInt_TwentyDigits_Refused", "");
    check(!gate_parse_int("", 0, &v), "ParseInt_Empty_Refused", "");
    check(!gate_parse_int("+-1", 3, &v), "ParseInt_TwoSigns_Refused", "");
    check(!gate_parse_int("1-", 2, &v), "ParseInt_TrailingSign_Refused", "");
}

static void scheduled_bursts(void)
{
    reset();
    expect("Caps_WithAfter_ListsAfter", "CAPS?", "OK CAPS AFTER");
    expect("BurstAfter_InRange_AcknowledgedWithDelay", "BURST 120 1000 AFTER 5000", "OK BURST 120 AFTER 5000");
    expect_u32("BurstAfter_InRange_ScheduledWithDelay", fired_after, 5000);
    expect_u32("BurstAfter_InRange_Counted", fired_pulses, 120);
    expect_u32("BurstAfter_InRange_AtItsFrequency", fired_hz, 1000);
    expect("BurstAfter_Waiting_StateOn", "STATE?", "OK STATE 1000 ON WDOG 1000");
    expect_u32("BurstAfter_Counted_FiresExactly", run_pulses(1000), 120);
    expect("BurstAfter_Zero_Acknowledged", "BURST 1 100000 AFTER 0", "OK BURST 1 AFTER 0");
    expect_u32("BurstAfter_Zero_ScheduledAtZero", fired_after, 0);
    expect("BurstAfter_Max_Acknowledged", "burst 1000000 100000 after 1000000", "OK BURST 1000000 AFTER 1000000");
    expect("BurstAfter_SpacesAndTabs_Accepted", " BURST\t3  1000 AFTER\t+300 \r", "OK BURST 3 AFTER 300");
    expect_u32("BurstAfter_PlusSign_ReadAsNumber", fired_after, 300);

    /* A later frequency command cancels the start still waiting (the HAL is told to stop first). */
    ask("BURST 10 1000 AFTER 20000");
    fire_calls = 0;
    expect("BurstAfter_ThenOff_Acknowledged", "OFF", "OK FREQ 0");
    expect_u32("BurstAfter_ThenOff_Stopped", fired_hz, 0);
    expect_u32("BurstAfter_ThenOff_OneStop", fire_calls, 1);
    ask("BURST 10 1000 AFTER 20000");
    expect("BurstAfter_ThenBurst_Acknowledged", "BURST 3 2000", "OK BURST 3");
    expect_u32("BurstAfter_ThenBurst_StartsAtOnce", fired_after, NO_AFTER_SEEN);
    expect_u32("BurstAfter_ThenBurst_NewCount", run_pulses(50), 3);
    ask("BURST 10 1000");
    run_pulses(4);
    ask("BURST 5 1000 AFTER 1000");
    expect_u32("BurstAfter_DuringBurst_NewCount", run_pulses(50), 5);

    /* Errors: range, syntax; a refused one changes nothing. */
    ask("OFF");
    expect("BurstAfter_AboveMaxDelay_Err2", "BURST 5 1000 AFTER 1000001", "ERR 2 RANGE");
    expect("BurstAfter_NegativeDelay_Err2", "BURST 5 1000 AFTER -1", "ERR 2 RANGE");
    expect("BurstAfter_ZeroPulses_Err2", "BURST 0 1000 AFTER 300", "ERR 2 RANGE");
    expect("BurstAfter_ZeroHz_Err2", "BURST 5 0 AFTER 300", "ERR 2 RANGE");
    expect("BurstAfter_DelayNotANumber_Err3", "BURST 5 1000 AFTER x", "ERR 3 SYNTAX");
    expect("BurstAfter_OtherWord_Err3", "BURST 5 1000 LATER 300", "ERR 3 SYNTAX");
    expect("BurstAfter_NoDelay_Err3", "BURST 5 1000 AFTER", "ERR 3 SYNTAX");
    expect("BurstAfter_ExtraWord_Err3", "BURST 5 1000 AFTER 300 NOW", "ERR 3 SYNTAX");
    expect("BurstAfter_DelayBeyondInt32_Err3", "BURST 5 1000 AFTER 2147483648", "ERR 3 SYNTAX");
    expect_u32("BurstAfter_Refused_NeverFired", fired_hz, 0);

    /* The watchdog watches the wait: a start still waiting when it trips never comes. */
    reset();
    gate_poll(&g, 10);
    ask("WDOG 50");
    ask("BURST 100 1000 AFTER 1000000");
    gate_poll(&g, 60);
    expect_u32("BurstAfter_WatchdogTime_StillArmed", fired_hz, 1000);
    gate_poll(&g, 61);
    expect_u32("BurstAfter_WatchdogTrips_Cancelled", fired_hz, 0);
    expect("BurstAfter_WatchdogTrips_Tripped", "STATE?", "OK STATE 0 OFF WDOG 50 TRIPPED");

    /* A chip without a scheduled start: refused as a gate older than it does, and not listed. */
    reply_count = 0;
    gate_init(&g, &hal_without_after, "OLD-1", 1000);
    expect("BurstAfter_ChipWithout_Err3", "BURST 5 1000 AFTER 300", "ERR 3 SYNTAX");
    expect_u32("BurstAfter_ChipWithout_NeverFired", fired_hz, 0);
    expect("Caps_ChipWithout_ListsNothing", "CAPS?", "OK CAPS");
    expect("Burst_ChipWithout_StillWorks", "BURST 5 1000", "OK BURST 5");
}

int main(void)
{
    commands_answer_as_the_protocol_says();
    errors_answer_as_the_protocol_says();
    bursts_count_exactly();
    later_command_ends_burst();
    watchdog_switches_off_after_silence();
    lines_split_long_and_not_ascii();
    numbers_parse_as_dotnet_does();
    scheduled_bursts();
    printf("gate core: %d passed, %d failed\n", passed, failed);
    return failed ? 1 : 0;
}
