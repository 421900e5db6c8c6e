using System.Globalization;
using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Planning;

namespace LaserEngrave.Devices.Execution;

/// <summary>
/// A timed line whose write completed later than the host stamped it: the computer stalled between deciding to send and
/// the write (another process, a page fault), so the line left that much later than its timing assumed, whatever was
/// planned. Beyond the edge tolerance that is a timing doubt: the laser goes off at once and the run can go on from there.
/// </summary>
internal static class LateWrite
{
    // Below this a write's own time (microseconds) or the clock's rounding: not a stall.
    private const double StallSeconds = 0.0001;

    /// <summary>Waits for <paramref name="lineWritten"/> and faults the run when it completed too late for its edge.</summary>
    /// <param name="lineWritten">When the line's write completed, on <paramref name="time"/>; null: the link cannot tell.</param>
    /// <param name="time">The run's clock (the machine's).</param>
    /// <param name="engravingStart">Where run seconds count from, a timestamp of <paramref name="time"/>.</param>
    /// <param name="writtenSeconds">When the host stamped the line, run seconds: what its timing was computed from.</param>
    /// <param name="lateSeconds">How late the line already was by that stamp (its effect against its edge), s.</param>
    /// <param name="timing">The run's timing (the burn speed that turns time into µm).</param>
    /// <param name="toleranceUm">The profile's edge tolerance.</param>
    /// <param name="what">What the line was to do, for the fault ("switch the laser on").</param>
    /// <param name="fault">The run's fault (the laser off first); returns what to throw.</param>
    /// <returns>How much later than stamped the write completed, s (0 when on time or unknown).</returns>
    public static async Task<double> CheckAsync(Task<long?> lineWritten, TimeProvider time, long engravingStart, double writtenSeconds, double lateSeconds, TimedSwitching timing, double toleranceUm, string what, Func<string, Exception> fault)
    {
        ArgumentNullException.ThrowIfNull(lineWritten);
        ArgumentNullException.ThrowIfNull(time);
        ArgumentNullException.ThrowIfNull(timing);
        ArgumentNullException.ThrowIfNull(fault);
        if (await lineWritten is not { } stamp)
        {
            return 0;
        }

        var late = time.GetElapsedTime(engravingStart, stamp).TotalSeconds - writtenSeconds;
        if (late <= StallSeconds)
        {
            return 0;
        }

        // The line may have left any time up to the write's completion: its effect is taken to be that much later.
        var lateUm = (Math.Max(0, lateSeconds) + late) * timing.BurnSpeed * timing.MicrostepUm;
        if (lateUm > toleranceUm)
        {
            throw fault(string.Create(CultureInfo.InvariantCulture,
                $"this computer stalled {Units.SecondsToMs(late):0.0} ms between timing a line to {what} and writing it, {Units.SecondsToMs(Math.Max(0, lateSeconds) + late):0.0} ms late in all, {lateUm:0.0} µm at the burn speed, beyond the profile's edge tolerance of {toleranceUm:0.###} µm: the laser was switched off at once for that run"));
        }

        return late;
    }
}
