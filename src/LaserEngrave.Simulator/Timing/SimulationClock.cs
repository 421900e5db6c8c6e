namespace LaserEngrave.Simulator.Timing;

/// <summary>The simulator's view of a <see cref="TimeProvider"/>: seconds since the machine started, and timers at those times.</summary>
internal sealed class SimulationClock
{
    private readonly long _origin;

    /// <param name="time">The clock of the devices' own waiting: motion, bytes on the wire.</param>
    /// <param name="hostTime">The clock the host lives on, for what measures the host (watchdog, gaps between bytes); the same by default.</param>
    public SimulationClock(TimeProvider time, TimeProvider? hostTime = null)
    {
        Time = time;
        _origin = time.GetTimestamp();
        Host = hostTime is null || hostTime == time ? this : new SimulationClock(hostTime);
    }

    public TimeProvider Time { get; }

    /// <summary>
    /// The host's clock. In-process the host shares the simulator's clock; attached to ports in virtual time the host is
    /// another process living in real time, so silence and gaps it causes are measured on the wall clock.
    /// </summary>
    public SimulationClock Host { get; }

    /// <summary>Seconds since the machine started.</summary>
    public double NowSeconds => (Time.GetTimestamp() - _origin) / (double)Time.TimestampFrequency;

    /// <summary>Tells a virtual clock that bytes moved, so it waits for quiet before jumping.</summary>
    public void Signal() => (Time as VirtualTimeProvider)?.NotifyActivity();

    /// <summary>Keeps a virtual clock still while the simulator works on something (no-op in real time).</summary>
    public ClockHold Hold(TimeSpan? limit = null) => (Time as VirtualTimeProvider)?.Hold(limit) ?? default;

    /// <summary>Runs <paramref name="action"/> once at <paramref name="atSeconds"/> (at once when that has passed).</summary>
    public ITimer At(double atSeconds, Action action) =>
        Time.CreateTimer(static s => ((Action)s!)(), action, Until(atSeconds), Timeout.InfiniteTimeSpan);

    /// <summary>Runs <paramref name="action"/> every <paramref name="period"/>, first after one period.</summary>
    public ITimer Every(TimeSpan period, Action action) =>
        Time.CreateTimer(static s => ((Action)s!)(), action, period, period);

    /// <summary>Completes at <paramref name="atSeconds"/>, to the tick (Task.Delay would round to whole milliseconds).</summary>
    /// <remarks>
    /// The timer is made before the first await, and the caller resumes inside the timer's callback (no thread-pool hop),
    /// where a virtual clock still counts it as running: time cannot move on between the timer firing and the caller's next step.
    /// </remarks>
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
        await done.Task.ConfigureAwait(false);
    }

    // Rounded up to whole ticks so that an event never runs before its time.
    private TimeSpan Until(double atSeconds)
    {
        var seconds = atSeconds - NowSeconds;
        return seconds <= 0 ? TimeSpan.Zero : TimeSpan.FromTicks((long)Math.Ceiling(seconds * TimeSpan.TicksPerSecond));
    }
}
