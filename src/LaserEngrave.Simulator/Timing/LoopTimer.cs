namespace LaserEngrave.Simulator.Timing;

/// <summary>A timer on a <see cref="SimulationLoop"/>'s heap; its callback runs on the loop when virtual time reaches it.</summary>
internal sealed class LoopTimer(SimulationLoop loop, TimerCallback callback, object? state) : ITimer
{
    // Guarded by the loop's lock: where it is in the loop's TimerHeap (-1: not waiting), when it is due, and the order it was set in.
    public int HeapIndex { get; set; } = -1;

    public long Due { get; set; }

    public long Sequence { get; set; }

    public long PeriodTicks { get; set; }

    public bool Disposed { get; set; }

    public bool Change(TimeSpan dueTime, TimeSpan period)
    {
        if (Disposed)
        {
            return false;
        }

        loop.Change(this, ToTicks(dueTime, nameof(dueTime)), ToTicks(period, nameof(period)));
        return true;
    }

    public void Fire() => callback(state);

    public void Dispose() => loop.Remove(this);

    public ValueTask DisposeAsync()
    {
        Dispose();
        return ValueTask.CompletedTask;
    }

    private static long ToTicks(TimeSpan span, string name)
    {
        if (span == Timeout.InfiniteTimeSpan)
        {
            return -1;
        }

        // The same limits as the system's timers (0 to 4294967294 ms), which also keeps due times from overflowing.
        return span < TimeSpan.Zero || span.TotalMilliseconds > uint.MaxValue - 1
            ? throw new ArgumentOutOfRangeException(name, span, "a timer time must be 0 to 4294967294 ms, or infinite")
            : span.Ticks;
    }
}
