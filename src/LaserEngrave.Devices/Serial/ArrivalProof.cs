using System.Diagnostics;

namespace LaserEngrave.Devices.Serial;

/// <summary>
/// What a real port's reader can prove about when bytes arrived: it stamps a read when it returns, which on a loaded
/// computer can be tens of milliseconds after the bytes were waiting; but a wait that timed out proves the port had
/// nothing waiting at its end. So the reader waits in short steps just after a read, and the next bytes arrived after the
/// latest such proof (<see cref="Wire.Serial.StampedRead.EarliestArrival"/>): a gap inside a frame counts only when proven.
/// </summary>
internal static class ArrivalProof
{
    /// <summary>The short waits' length, ms: the finest gap that can be proven.</summary>
    public const int StepMs = 2;

    /// <summary>How long after a read the waits stay short, ms: past the partial-frame timeout (10 ms), with room.</summary>
    public const int WindowMs = 24;

    /// <summary>How long the next wait may be: short just after a read (<see cref="WindowMs"/>), else <paramref name="idleMs"/>.</summary>
    /// <param name="lastRead">When the previous read returned (<see cref="long.MinValue"/>: none yet), a <see cref="Stopwatch"/> timestamp.</param>
    /// <param name="now">Now, a <see cref="Stopwatch"/> timestamp.</param>
    /// <param name="idleMs">The wait when no read is recent.</param>
    public static int PollTimeoutMs(long lastRead, long now, int idleMs) =>
        lastRead != long.MinValue && now - lastRead < WindowMs * Stopwatch.Frequency / 1000 ? StepMs : idleMs;

    /// <summary>The latest time the port was proven quiet, after a wait begun at <paramref name="waitBegan"/> timed out after <paramref name="timeoutMs"/>.</summary>
    /// <remarks>The kernel looks once more when the time is up, so nothing was waiting at least that long after the wait began.</remarks>
    public static long QuietAfterTimeout(long quietAt, long waitBegan, int timeoutMs) =>
        Math.Max(quietAt, waitBegan + (timeoutMs * Stopwatch.Frequency / 1000));

    /// <summary>
    /// The earliest the bytes of a read can have arrived: the latest quiet proof since the read before, or (without one)
    /// that read's own stamp, which proves no gap at all.
    /// </summary>
    /// <param name="quietAt">The latest quiet proof since the read before (<see cref="long.MinValue"/>: none).</param>
    /// <param name="previousRead">When the read before returned (<see cref="long.MinValue"/>: none).</param>
    /// <param name="returned">When this read returned.</param>
    public static long Earliest(long quietAt, long previousRead, long returned) =>
        Math.Min(returned, quietAt != long.MinValue ? quietAt : previousRead != long.MinValue ? previousRead : returned);
}
