using System.Diagnostics;

namespace LaserEngrave.Simulator.Timing;

/// <summary>A discrete-event clock: time stands still while the system works and jumps to the earliest timer once it is quiet.</summary>
/// <remarks>
/// <para>
/// Shared by the simulator and the host code under test. Every timer made through <see cref="CreateTimer"/> (which
/// <c>Task.Delay</c>, <c>WaitAsync</c> and <c>CancellationTokenSource</c> use when given this provider) fires in
/// virtual-time order. A background thread advances the clock to the earliest pending timer once the system has been
/// quiet for <see cref="QuietPeriod"/> of wall-clock time, so an hour-long job simulates in seconds and a device that
/// goes silent still lets a host timeout fire.
/// </para>
/// <para>
/// Quiet means all of: no <see cref="NotifyActivity"/> call, no timer created, changed or fired, no timer callback
/// still running and no <see cref="Hold"/> taken during the quiet period, and no work item waiting in the thread pool
/// at its end. The last condition keeps the clock still while a continuation (a reply being parsed, the next command
/// being sent) is queued but has not run yet; holds cover code that is running but slow (a loaded machine, the JIT),
/// which would otherwise let the clock jump past its own next step and fire a spurious timeout. On Linux, when the host
/// shares the process, no other thread of the process may be running or waiting for a CPU either (<see cref="RunnableThreads"/>): that covers a host thread
/// descheduled between reading a reply and sending its next command, which no hold marks. A callback or hold
/// older than <see cref="BlockedCallbackLimit"/> stops holding the clock, so nothing can freeze time for good.
/// </para>
/// </remarks>
public sealed class VirtualTimeProvider : TimeProvider, IDisposable
{
    /// <summary>Wall-clock quiet time after which the clock jumps when none is given.</summary>
    public static readonly TimeSpan DefaultQuietPeriod = TimeSpan.FromMilliseconds(1);

    /// <summary>A timer callback running, or a hold kept, longer than this (wall clock) no longer keeps the clock still.</summary>
    public static readonly TimeSpan BlockedCallbackLimit = TimeSpan.FromMilliseconds(250);

    // A plain monitor rather than System.Threading.Lock: the advancer thread needs Monitor.Wait/PulseAll.
    private readonly object _gate = new();
    private readonly PriorityQueue<(VirtualTimer Timer, long Version), (long Due, long Sequence)> _queue = new();
    // Running timer callbacks and holds, by id: the wall-clock timestamp when they began and how long they may hold.
    private readonly Dictionary<long, (long Started, TimeSpan Limit)> _holds = [];
    private readonly DateTimeOffset _start;
    private readonly bool _waitForRunnableThreads;
    private readonly Thread _advancer;
    private long _nowTicks;
    private long _activity;
    private long _sequence;
    private long _callbackIds;
    private long _firedTimers;
    private bool _disposed;

    /// <param name="start">Wall-clock time at virtual time zero; now by default.</param>
    /// <param name="quietPeriod">How long the system must be quiet before the clock jumps; <see cref="DefaultQuietPeriod"/> by default.</param>
    /// <param name="waitForRunnableThreads">
    /// Also wait while another thread of this process is runnable (Linux). Right when the host shares the process; wrong when
    /// it does not (the simulator on real ports), where the serial library's polling threads would only slow the clock.
    /// </param>
    public VirtualTimeProvider(DateTimeOffset? start = null, TimeSpan? quietPeriod = null, bool waitForRunnableThreads = true)
    {
        var quiet = quietPeriod ?? DefaultQuietPeriod;
        if (quiet <= TimeSpan.Zero)
        {
            throw new ArgumentOutOfRangeException(nameof(quietPeriod), quiet, "the quiet period must be above zero");
        }

        _start = start ?? System.GetUtcNow();
        QuietPeriod = quiet;
        _waitForRunnableThreads = waitForRunnableThreads;
        _advancer = new Thread(Advance) { IsBackground = true, Name = "virtual time" };
        _advancer.Start();
    }

    public TimeSpan QuietPeriod { get; }

    /// <summary>Virtual time since the clock was made.</summary>
    public TimeSpan Elapsed => TimeSpan.FromTicks(Volatile.Read(ref _nowTicks));

    /// <summary>Number of timers fired so far (each firing of a periodic timer counts).</summary>
    public long FiredTimers => Interlocked.Read(ref _firedTimers);

    /// <summary>Timers waiting to fire.</summary>
    public int PendingTimers
    {
        get
        {
            lock (_gate)
            {
                DropStaleHead();
                var live = 0;
                foreach (var (element, _) in _queue.UnorderedItems)
                {
                    if (element.Timer.IsLive(element.Version))
                    {
                        live++;
                    }
                }

                return live;
            }
        }
    }

    public override long TimestampFrequency => TimeSpan.TicksPerSecond;

    public override DateTimeOffset GetUtcNow() => _start + Elapsed;

    public override long GetTimestamp() => Volatile.Read(ref _nowTicks);

    /// <summary>Tells the clock that something happened (a byte was sent or delivered), so it waits for quiet again.</summary>
    public void NotifyActivity() => Interlocked.Increment(ref _activity);

    /// <summary>Keeps the clock still until the hold is disposed, or <paramref name="limit"/> of wall-clock time has passed.</summary>
    /// <remarks>For code that must finish a step before virtual time may move on, e.g. parsing bytes just received.</remarks>
    /// <param name="limit">Longest the hold counts; <see cref="BlockedCallbackLimit"/> by default.</param>
    public ClockHold Hold(TimeSpan? limit = null)
    {
        lock (_gate)
        {
            var id = ++_callbackIds;
            _holds[id] = (Stopwatch.GetTimestamp(), limit ?? BlockedCallbackLimit);
            Interlocked.Increment(ref _activity);
            return new ClockHold(this, id);
        }
    }

    public override ITimer CreateTimer(TimerCallback callback, object? state, TimeSpan dueTime, TimeSpan period)
    {
        ArgumentNullException.ThrowIfNull(callback);
        var timer = new VirtualTimer(this, callback, state, ExecutionContext.Capture());
        timer.Change(dueTime, period);
        return timer;
    }

    /// <summary>Stops the clock; pending timers never fire.</summary>
    public void Dispose()
    {
        lock (_gate)
        {
            _disposed = true;
            _queue.Clear();
            Monitor.PulseAll(_gate);
        }
    }

    private static long ToTicks(TimeSpan span, string name)
    {
        if (span == Timeout.InfiniteTimeSpan)
        {
            return -1;
        }

        // The same limits as the system's timers (0 to 4294967294 ms), which also keeps due times from overflowing.
        if (span < TimeSpan.Zero || span.TotalMilliseconds > uint.MaxValue - 1)
        {
            throw new ArgumentOutOfRangeException(name, span, "a timer time must be 0 to 4294967294 ms, or infinite");
        }

        return span.Ticks;
    }

    private bool Change(VirtualTimer timer, TimeSpan dueTime, TimeSpan period)
    {
        var dueTicks = ToTicks(dueTime, nameof(dueTime));
        var periodTicks = ToTicks(period, nameof(period));
        lock (_gate)
        {
            if (timer.Disposed)
            {
                return false;
            }

            Interlocked.Increment(ref _activity);
            var version = ++timer.Version;
            timer.PeriodTicks = periodTicks > 0 ? periodTicks : 0;
            if (_disposed || dueTicks < 0)
            {
                return true;
            }

            var due = _nowTicks + dueTicks;
            if (dueTicks == 0)
            {
                // Due now: fire at once, as a real timer would, instead of waiting for quiet.
                Fire(timer);
                if (timer.PeriodTicks == 0)
                {
                    return true;
                }

                due += timer.PeriodTicks;
            }

            _queue.Enqueue((timer, version), (due, _sequence++));
            Monitor.PulseAll(_gate);
            return true;
        }
    }

    private void Remove(VirtualTimer timer)
    {
        lock (_gate)
        {
            timer.Disposed = true;
            timer.Version++;
            Interlocked.Increment(ref _activity);
        }
    }

    // Caller holds _gate.
    private void Fire(VirtualTimer timer)
    {
        var id = ++_callbackIds;
        _holds[id] = (Stopwatch.GetTimestamp(), BlockedCallbackLimit);
        Interlocked.Increment(ref _activity);
        Interlocked.Increment(ref _firedTimers);
        ThreadPool.UnsafeQueueUserWorkItem(
            static s =>
            {
                try
                {
                    s.Timer.Invoke();
                }
                finally
                {
                    s.Provider.CallbackDone(s.Id);
                }
            },
            (Provider: this, Timer: timer, Id: id),
            preferLocal: false);
    }

    internal void Release(long id) => CallbackDone(id);

    private void CallbackDone(long id)
    {
        lock (_gate)
        {
            _holds.Remove(id);
            Interlocked.Increment(ref _activity);
        }
    }

    // Caller holds _gate.
    private void DropStaleHead()
    {
        while (_queue.TryPeek(out var head, out _) && !head.Timer.IsLive(head.Version))
        {
            _queue.Dequeue();
        }
    }

    // Caller holds _gate.
    private bool CallbacksHoldClock()
    {
        foreach (var (started, limit) in _holds.Values)
        {
            if (Stopwatch.GetElapsedTime(started) < limit)
            {
                return true;
            }
        }

        return false;
    }

    private void Advance()
    {
        RunnableThreads.IgnoreCurrentThread();
        try
        {
            AdvanceUntilDisposed();
        }
        finally
        {
            RunnableThreads.ForgetCurrentThread();
        }
    }

    private void AdvanceUntilDisposed()
    {
        while (true)
        {
            long seen;
            lock (_gate)
            {
                DropStaleHead();
                while (!_disposed && _queue.Count == 0)
                {
                    Monitor.Wait(_gate);
                    DropStaleHead();
                }

                if (_disposed)
                {
                    return;
                }

                seen = Interlocked.Read(ref _activity);
            }

            Thread.Sleep(QuietPeriod);

            // Looked at outside the lock: reading /proc must not keep other threads from arming timers.
            var runnable = _waitForRunnableThreads && RunnableThreads.AnyOtherRunnable();
            lock (_gate)
            {
                if (_disposed)
                {
                    return;
                }

                if (Interlocked.Read(ref _activity) != seen || CallbacksHoldClock() || ThreadPool.PendingWorkItemCount > 0 || runnable)
                {
                    continue;
                }

                DropStaleHead();
                if (!_queue.TryDequeue(out var next, out var at))
                {
                    continue;
                }

                Volatile.Write(ref _nowTicks, Math.Max(_nowTicks, at.Due));
                if (next.Timer.PeriodTicks > 0)
                {
                    _queue.Enqueue(next, (at.Due + next.Timer.PeriodTicks, _sequence++));
                }

                Fire(next.Timer);
            }
        }
    }

    private sealed class VirtualTimer(VirtualTimeProvider owner, TimerCallback callback, object? state, ExecutionContext? context) : ITimer
    {
        private static readonly ContextCallback RunCallback = s =>
        {
            var timer = (VirtualTimer)s!;
            timer.Callback(timer.State);
        };

        // Guarded by the owner's lock.
        public long Version { get; set; }

        public long PeriodTicks { get; set; }

        public bool Disposed { get; set; }

        private TimerCallback Callback { get; } = callback;

        private object? State { get; } = state;

        public bool IsLive(long version) => !Disposed && Version == version;

        public bool Change(TimeSpan dueTime, TimeSpan period) => owner.Change(this, dueTime, period);

        public void Invoke()
        {
            if (context is null)
            {
                Callback(State);
            }
            else
            {
                ExecutionContext.Run(context, RunCallback, this);
            }
        }

        public void Dispose() => owner.Remove(this);

        public ValueTask DisposeAsync()
        {
            Dispose();
            return ValueTask.CompletedTask;
        }
    }
}
