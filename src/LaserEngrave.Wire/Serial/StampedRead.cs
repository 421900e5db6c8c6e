namespace LaserEngrave.Wire.Serial;

/// <summary>What one read of a link returned: how many bytes, and when they arrived.</summary>
/// <param name="Count">Bytes read; 0 when the link is closed.</param>
/// <param name="ArrivalTimestamp">When they arrived, as a timestamp of the clock the reader asked for.</param>
public readonly record struct StampedRead(int Count, long ArrivalTimestamp)
{
    /// <summary>
    /// When the link can only bound the arrival (a real port's reader stamps a read when it returned, and may have been
    /// held up before it looked): the bytes arrived no earlier than this, the last time the link saw nothing waiting.
    /// Null: they arrived exactly at <see cref="ArrivalTimestamp"/> (a simulated link knows). A gap between two pieces of a
    /// frame is proven only from this bound, so a reader's own delay never splits a frame.
    /// </summary>
    public long? EarliestArrival { get; init; }

    /// <summary>Carries a stamp taken on <paramref name="stampClock"/> over to <paramref name="time"/> by its age.</summary>
    /// <remarks>The same clock keeps the stamp as it is; another one (a real port read by a test's fake clock) gets "now minus the age".</remarks>
    public static long OnClock(long stamp, TimeProvider stampClock, TimeProvider time)
    {
        ArgumentNullException.ThrowIfNull(stampClock);
        ArgumentNullException.ThrowIfNull(time);
        if (ReferenceEquals(stampClock, time))
        {
            return stamp;
        }

        var age = stampClock.GetElapsedTime(stamp);
        return time.GetTimestamp() - (long)(age.TotalSeconds * time.TimestampFrequency);
    }
}
