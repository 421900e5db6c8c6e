namespace LaserEngrave.Simulator.Timing;

/// <summary>The simulator's view of a <see cref="TimeProvider"/>: seconds since the machine started, and timers at those times.</summary>
internal sealed class SimulationClock
{
    private readonly long _origin;

    public SimulationClock(TimeProvider time)
    {
        Time = time;
        _origin = time.GetTimestamp();
    }

    public TimeProvider Time { get; }

    /// <summary>Seconds since the machine started.</summary>
    public double NowSeconds => SecondsAt(Time.GetTimestamp());

    /// <summary>A timestamp of <see cref="Time"/> as seconds since the machine started.</summary>
    public double SecondsAt(long timestamp) => (timestamp - _origin) / (double)Time.TimestampFrequency;

    /// <summary>Runs <paramref name="action"/> once at <paramref name="atSeconds"/> (at once when that has passed).</summary>
    public ITimer At(double atSeconds, Action action) =>
        Time.CreateTimer(static s => ((Action)s!)(), action, Until(atSeconds), Timeout.InfiniteTimeSpan);

    /// <summary>Runs <paramref name="action"/> every <paramref name="period"/>, first after one period.</summary>
    public ITimer Every(TimeSpan period, Action action) =>
        Time.CreateTimer(static s => ((Action)s!)(), action, period, period);

    /// <summary>Completes at <paramref name="atSeconds"/>, to the tick (Task.Delay would round to whole milliseconds).</summary>
    public async Task DelayUntil(double atSeconds, CancellationToken cancellationToken)
    {
        var wait = Until(atSeconds);
        if (wait == TimeSpan.Zero)
        {
            return;
        }

        var done = new TaskCompletionSource();
        await using var timer = Time.CreateTimer(static s => ((TaskCompletionSource)s!).TrySetResult(), done, wait, Timeout.InfiniteTimeSpan);
        await using var registration = cancellationToken.Register(static s => ((TaskCompletionSource)s!).TrySetCanceled(), done);
        await done.Task;
    }

    // Rounded up to whole ticks so that an event never runs before its time.
    private TimeSpan Until(double atSeconds)
    {
        var seconds = atSeconds - NowSeconds;
        return seconds <= 0 ? TimeSpan.Zero : TimeSpan.FromTicks((long)Math.Ceiling(seconds * TimeSpan.TicksPerSecond));
    }
}
