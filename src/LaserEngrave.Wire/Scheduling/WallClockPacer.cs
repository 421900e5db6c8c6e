using System.Diagnostics;

namespace LaserEngrave.Wire.Scheduling;

/// <summary>
/// Runs actions at their instants on the wall clock to a fraction of a millisecond: one thread for the process that
/// sleeps until just before the next instant and waits the rest out on the high-resolution timestamp. The host's timed
/// switching waits on it (<see cref="PreciseDelay"/>), and so do the wall-clock simulator's events.
/// </summary>
/// <remarks>
/// The system's timers are too coarse for commands and replies planned to the millisecond: .NET counts their due times
/// in whole milliseconds or the coarse tick (15.6 ms on Windows) and hands each callback to the thread pool; measured on
/// Linux, <c>Task.Delay</c> ended 2.3 ms late at the median and up to 8 ms late on a loaded computer. So a simulated
/// reply left 2-3 ms late on every wait, and the host spun out the last 16 ms of every timed wait on a thread-pool
/// thread, up to 16 ms of a core per timed command, taken from the devices' side on a two-core computer. Here only the
/// last 2 ms are spun (on Windows, whose waits end on its 15.6 ms tick, the last 17 ms), on one thread. The actions run
/// on this thread, which the whole process shares, so they must be short and never block: a simulated device acting, a
/// reply handed to its link's writer, or the host's continuation after a timed wait, which sends its command and awaits
/// the next thing.
/// </remarks>
public sealed class WallClockPacer
{
    // Monitor.Wait sleeps to the millisecond on Linux and macOS, to the timer tick (15.6 ms by default) on Windows; the
    // last stretch is waited out on the timestamp.
    private static readonly long SpinTicks = OperatingSystem.IsWindows() ? Stopwatch.Frequency / 60 : Stopwatch.Frequency / 500;

    private readonly object _lock = new();
    private readonly PriorityQueue<Entry, (long Due, long Sequence)> _queue = new();
    private long _sequence;

    private WallClockPacer()
    {
        var thread = new Thread(Run) { IsBackground = true, Name = "wall-clock pacer", Priority = ThreadPriority.AboveNormal };
        thread.Start();
    }

    /// <summary>The process' pacer.</summary>
    public static WallClockPacer Shared { get; } = new();

    /// <summary>Runs <paramref name="action"/> on the pacer's thread at <paramref name="dueTimestamp"/> (<see cref="Stopwatch"/> ticks); dispose the result to cancel it.</summary>
    public IDisposable Schedule(long dueTimestamp, Action action)
    {
        var entry = new Entry(action);
        lock (_lock)
        {
            _queue.Enqueue(entry, (dueTimestamp, _sequence++));
            Monitor.Pulse(_lock);
        }

        return entry;
    }

    private void Run()
    {
        while (true)
        {
            Entry? due = null;
            lock (_lock)
            {
                while (due is null)
                {
                    if (!_queue.TryPeek(out var head, out var at))
                    {
                        Monitor.Wait(_lock);
                        continue;
                    }

                    if (head.Cancelled)
                    {
                        _queue.Dequeue();
                        continue;
                    }

                    var remaining = at.Due - Stopwatch.GetTimestamp();
                    if (remaining <= 0)
                    {
                        due = _queue.Dequeue();
                    }
                    else if (remaining > SpinTicks)
                    {
                        // Woken early by a new, earlier event or by the wait's end; either way look again.
                        Monitor.Wait(_lock, TimeSpan.FromSeconds((double)(remaining - SpinTicks) / Stopwatch.Frequency));
                    }
                    else
                    {
                        Monitor.Exit(_lock);
                        try
                        {
                            var until = at.Due;
                            while (Stopwatch.GetTimestamp() < until)
                            {
                                Thread.SpinWait(20);
                            }
                        }
                        finally
                        {
                            Monitor.Enter(_lock);
                        }
                    }
                }
            }

            try
            {
                due.Run();
            }
            catch (Exception ex)
            {
                // An event's failure is its own: it must not stop the clock of every other one.
                Trace.TraceError($"wall-clock pacer: an action failed: {ex}");
            }
        }
    }

    private sealed class Entry(Action action) : IDisposable
    {
        private volatile bool _cancelled;

        public bool Cancelled => _cancelled;

        public void Run()
        {
            if (!_cancelled)
            {
                action();
            }
        }

        public void Dispose() => _cancelled = true;
    }
}
