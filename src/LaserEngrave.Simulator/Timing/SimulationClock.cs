using System.Diagnostics;
using LaserEngrave.Wire.Scheduling;

namespace LaserEngrave.Simulator.Timing;

/// <summary>The simulator's view of a <see cref="TimeProvider"/>: seconds since the machine started, and timers at those times.</summary>
/// <remarks>
/// In virtual time every event runs at its exact instant. On the wall clock (a host in another process) an event's code
/// runs when this process gets to it: the waits go through <see cref="WallClockPacer"/> (the system's timers are a few
/// milliseconds late), and while an event's code runs the clock reads the instant it is for, not the moment the process
/// got to it, so that a device acts as of the time its model says (a position read, a reply's departure) even when a
/// loaded computer runs it late. A late event thus makes its reply late only by its own lateness, never by the sum of
/// every late step before it.
/// </remarks>
internal sealed class SimulationClock
{
    // The event being run on this thread, and its instant (wall clock only).
    [ThreadStatic]
    private static SimulationClock? t_eventClock;

    [ThreadStatic]
    private static double t_eventSeconds;

    private readonly long _origin;
    private readonly bool _wallClock;

    public SimulationClock(TimeProvider time)
    {
        Time = time;
        _origin = time.GetTimestamp();
        _wallClock = ReferenceEquals(time, TimeProvider.System);
    }

    public TimeProvider Time { get; }

    /// <summary>Whether this is the wall clock (a host in another process), whose events <see cref="WallClockPacer"/> runs.</summary>
    public bool IsWallClock => _wallClock;

    /// <summary>Seconds since the machine started (on the wall clock, inside an event: the event's instant).</summary>
    public double NowSeconds => ReferenceEquals(t_eventClock, this) ? t_eventSeconds : SecondsAt(Time.GetTimestamp());

    /// <summary>A timestamp of <see cref="Time"/> as seconds since the machine started.</summary>
    public double SecondsAt(long timestamp) => (timestamp - _origin) / (double)Time.TimestampFrequency;

    /// <summary>Runs <paramref name="action"/> once at <paramref name="atSeconds"/> (at once when that has passed).</summary>
    public ITimer At(double atSeconds, Action action) =>
        _wallClock
            ? new PacedTimer(WallClockPacer.Shared.Schedule(TimestampAt(atSeconds), () => RunAt(atSeconds, action)))
            : Time.CreateTimer(static s => ((Action)s!)(), action, Until(atSeconds), Timeout.InfiniteTimeSpan);

    /// <summary>Runs <paramref name="action"/> every <paramref name="period"/>, first after one period.</summary>
    public ITimer Every(TimeSpan period, Action action) =>
        Time.CreateTimer(static s => ((Action)s!)(), action, period, period);

    /// <summary>Runs <paramref name="action"/> as the event of <paramref name="atSeconds"/>, an instant that has come.</summary>
    /// <remarks>In virtual time the clock is at that instant already; on the wall clock it reads that instant meanwhile.</remarks>
    public void RunAt(double atSeconds, Action action)
    {
        if (!_wallClock)
        {
            action();
            return;
        }

        var (clock, seconds) = (t_eventClock, t_eventSeconds);
        (t_eventClock, t_eventSeconds) = (this, Math.Min(atSeconds, SecondsAt(Time.GetTimestamp())));
        try
        {
            action();
        }
        finally
        {
            (t_eventClock, t_eventSeconds) = (clock, seconds);
        }
    }

    /// <summary>Completes at <paramref name="atSeconds"/>, to the tick (Task.Delay would round to whole milliseconds).</summary>
    public async Task DelayUntil(double atSeconds, CancellationToken cancellationToken)
    {
        var wait = Until(atSeconds);
        if (wait == TimeSpan.Zero)
        {
            return;
        }

        var done = new TaskCompletionSource();
        await using var timer = _wallClock
            ? new PacedTimer(WallClockPacer.Shared.Schedule(TimestampAt(atSeconds), () => done.TrySetResult()))
            : Time.CreateTimer(static s => ((TaskCompletionSource)s!).TrySetResult(), done, wait, Timeout.InfiniteTimeSpan);
        await using var registration = cancellationToken.Register(static s => ((TaskCompletionSource)s!).TrySetCanceled(), done);
        await done.Task;
    }

    /// <summary>Whether <paramref name="atSeconds"/> has come: <see cref="DelayUntil"/> would not wait.</summary>
    public bool IsDue(double atSeconds) => Until(atSeconds) == TimeSpan.Zero;

    // Rounded up to whole ticks so that an event never runs before its time.
    private TimeSpan Until(double atSeconds)
    {
        var seconds = atSeconds - NowSeconds;
        return seconds <= 0 ? TimeSpan.Zero : TimeSpan.FromTicks((long)Math.Ceiling(seconds * TimeSpan.TicksPerSecond));
    }

    // The wall clock's timestamps are the Stopwatch's (TimeProvider.System's).
    private long TimestampAt(double atSeconds) =>
        _origin + (long)Math.Ceiling(atSeconds * Stopwatch.Frequency);

    private sealed class PacedTimer(IDisposable scheduled) : ITimer
    {
        public bool Change(TimeSpan dueTime, TimeSpan period) => throw new NotSupportedException("a paced event is not moved: cancel it and schedule another");

        public void Dispose() => scheduled.Dispose();

        public ValueTask DisposeAsync()
        {
            scheduled.Dispose();
            return ValueTask.CompletedTask;
        }
    }
}
