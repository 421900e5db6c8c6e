using LaserEngrave.Wire.Scheduling;


namespace LaserEngrave.Simulator.Timing;

/// <summary>The clock of a <see cref="SimulationLoop"/>: virtual time, timers on the loop's heap, work on the loop's thread.</summary>
/// <remarks>
/// Host code finds the loop through <see cref="TaskRunner.For"/> (this clock is also the runner), so a reader loop or a
/// keepalive started by device code runs on the loop, and an operation run through it moves virtual time. Timers keep
/// full 100 ns ticks (<c>Task.Delay</c> itself rounds to whole milliseconds). Timers can only be made on the loop.
/// </remarks>
public sealed class VirtualTimeProvider : TimeProvider, ITaskRunner, IHostLateness, IDisposable
{
    private readonly DateTimeOffset _start;

    /// <param name="start">Wall-clock time at virtual time zero (what logs show as the start of a run); now by default.</param>
    /// <param name="paced">Never ahead of the wall clock (<see cref="SimulationLoop"/>), for a live view.</param>
    /// <param name="wallClock">The wall clock a paced loop keeps to (the system's by default; a fake one in tests).</param>
    public VirtualTimeProvider(DateTimeOffset? start = null, bool paced = false, TimeProvider? wallClock = null)
    {
        _start = start ?? (wallClock ?? System).GetUtcNow();
        Loop = new SimulationLoop(paced: paced, wallClock: wallClock);
    }

    /// <summary>How late the host wakes from each timed wait (<see cref="IHostLateness"/>); null: never late.</summary>
    public Func<TimeSpan>? HostLateness { get; set; }

    /// <inheritdoc />
    public TimeSpan NextLateness() => HostLateness?.Invoke() ?? TimeSpan.Zero;

    /// <summary>The loop this clock belongs to.</summary>
    public SimulationLoop Loop { get; }

    /// <summary>Virtual time since the clock was made.</summary>
    public TimeSpan Elapsed => TimeSpan.FromTicks(Loop.NowTicks);

    public override long TimestampFrequency => TimeSpan.TicksPerSecond;

    public override DateTimeOffset GetUtcNow() => _start + Elapsed;

    public override long GetTimestamp() => Loop.NowTicks;

    public override ITimer CreateTimer(TimerCallback callback, object? state, TimeSpan dueTime, TimeSpan period)
    {
        ArgumentNullException.ThrowIfNull(callback);
        var timer = Loop.CreateTimer(callback, state);
        timer.Change(dueTime, period);
        return timer;
    }

    public Task Start(Func<Task> loop) => Loop.Start(loop);

    public Task<T> Run<T>(Func<Task<T>> operation) => Loop.Run(operation);

    /// <summary>Stops the loop; pending timers never fire.</summary>
    public void Dispose() => Loop.Dispose();
}
