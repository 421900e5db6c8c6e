using LaserEngrave.Simulator.Timing;

namespace LaserEngrave.Simulator.LaserGate;

/// <summary>
/// The reference gate firmware's timing (firmware/gate, docs/gate-firmware.md), which the twin's gate takes as its own:
/// the figures are the ATmega328P image's, measured cycle by cycle in simavr by <c>make -C firmware/gate test-avr</c>
/// (firmware/gate/sim/avr_vectors.py; the figures in build/avr-figures.txt), and the period grid is the firmware's
/// own arithmetic (firmware/gate/atmega328p/main.c, <c>fired_period_cycles</c>).
/// </summary>
public static class GateFirmwareTiming
{
    /// <summary>The gate's clock, Hz (a 16 MHz crystal).</summary>
    public const double ClockHz = 16_000_000;

    /// <summary>
    /// Cycles from a line's last stop bit until the firmware has stopped the pulse train, besides 110 cycles a byte of
    /// the line ('\n' included): receiving, trimming, splitting and reading its numbers take about that much a byte. Measured
    /// in a trace build (-DGATE_TRACE toggles PB2 there) over OFF, FREQ and BURST lines of 4 to 18 bytes: OFF 814 cycles
    /// (4 bytes), FREQ 1000 1431 (10), BURST 120 1000 2122 (15), BURST 120000 1000 2487 (18); the model is within 36
    /// cycles (2.3 µs) of every one.
    /// </summary>
    public const int StopBaseCyclesOff = 374;

    /// <inheritdoc cref="StopBaseCyclesOff"/>
    public const int StopBaseCyclesFrequency = 331;

    /// <inheritdoc cref="StopBaseCyclesOff"/>
    public const int StopBaseCyclesBurst = 507;

    /// <summary>Cycles a byte of the line adds (see <see cref="StopBaseCyclesOff"/>).</summary>
    public const int CyclesPerLineByte = 110;

    /// <summary>
    /// Cycles from the train stopped to the first pulse of the new one: choosing the prescaler, one 32-bit division for
    /// the period, starting Timer1 (812-867 cycles measured; the first pulse follows the line's last stop bit by 123.5 µs
    /// for FREQ 1 to 203.9 µs for BURST 1000 100000, make -C firmware/gate test-avr).
    /// </summary>
    public const int StartCycles = 830;

    /// <summary>The firmware's time from a line's last stop bit to what it does, seconds: the first pulse for a frequency
    /// command that fires (<paramref name="fires"/>), else the train stopped (and the reply starting, for any line).</summary>
    /// <param name="command">Which command the line is (<see cref="GateCommand"/>).</param>
    /// <param name="lineBytes">The line's length in bytes, its line end included.</param>
    /// <param name="fires">Whether the command starts a pulse train (FREQ above 0, BURST).</param>
    internal static double ProcessingSeconds(GateCommand command, int lineBytes, bool fires)
    {
        var stop = (command switch
        {
            GateCommand.Off => StopBaseCyclesOff,
            GateCommand.Burst => StopBaseCyclesBurst,
            _ => StopBaseCyclesFrequency,
        }) + (CyclesPerLineByte * lineBytes);
        return (stop + (fires ? StartCycles : 0)) / ClockHz;
    }

    /// <summary>The firmware's processing of a written line as a replay's round trips need it, read as the twin's gate reads it (<paramref name="commands"/>: the profile's spellings; a scheduled burst's wait is not part of it).</summary>
    internal static double ProcessingSeconds(GateCommandSet commands, ReadOnlySpan<byte> line)
    {
        var text = System.Text.Encoding.ASCII.GetString(line).TrimEnd('\n').TrimEnd('\r').Trim();
        return VirtualLaserGate.FirmwareProcessingSeconds(commands, text, line.Length);
    }

    /// <summary>
    /// The period the firmware fires for <paramref name="hz"/>, seconds: a whole number of ticks of Timer1, ticks =
    /// round(16 MHz / (prescaler x hz)) with the smallest prescaler of 1, 8, 64, 256 whose count fits 16 bits (245 Hz
    /// and above: 62.5 ns steps; 31-244 Hz: 0.5 µs; 4-30 Hz: 4 µs; 1-3 Hz: 16 µs). 1000 Hz and 100 kHz are exact;
    /// 3333 Hz fires every 300.000 µs (3333.33 Hz) instead of 300.030 µs.
    /// </summary>
    public static double FiredPeriodSeconds(int hz)
    {
        ArgumentOutOfRangeException.ThrowIfLessThan(hz, 1);
        var prescaler = (long)Math.Round(TickSeconds(hz) * ClockHz);
        var perTick = 16_000_000L / prescaler;
        var ticks = (perTick + (hz / 2)) / hz;

        // A frequency the grid fires exactly is 1 / hz to the last bit, as the twin has always timed it.
        return ticks * hz == perTick ? 1.0 / hz : ticks * prescaler / ClockHz;
    }

    /// <summary>One tick of the firmware's pulse timer at <paramref name="hz"/>, seconds (its prescaler over the clock).</summary>
    public static double TickSeconds(int hz) => (hz >= 245 ? 1 : hz >= 31 ? 8 : hz >= 4 ? 64 : 256) / ClockHz;

    /// <summary>The frequency the firmware actually fires for <paramref name="hz"/> (0 stays 0), Hz: hz itself where the grid is exact.</summary>
    public static double FiredHz(int hz)
    {
        if (hz <= 0)
        {
            return 0;
        }

        var period = FiredPeriodSeconds(hz);
        return period == 1.0 / hz ? hz : 1 / period;
    }
}
