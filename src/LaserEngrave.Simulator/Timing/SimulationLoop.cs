using System.Globalization;

namespace LaserEngrave.Simulator.Timing;

/// <summary>
/// One thread that runs the whole simulation, host and devices: a queue of ready work and a heap of timers on one
/// virtual clock. Work runs first; when none is left the clock jumps to the next timer; when neither is left while an
/// operation is still under way, that is a deadlock, reported instead of waited for.
/// </summary>
/// <remarks>
/// <para>
/// It is the <see cref="SynchronizationContext"/> of its thread, so every <c>await</c> in code it runs comes back to it
/// (so long as nobody writes <c>ConfigureAwait(false)</c>), and <see cref="VirtualTimeProvider"/> puts every timer on
/// its heap, so <c>Task.Delay</c>, <c>CancellationTokenSource</c> timeouts and the devices' own events all fire in
/// virtual-time order. Same inputs and seed, same sequence of steps: the result does not depend on the machine's load.
/// </para>
/// <para>
/// Virtual time moves only while an operation started with <see cref="Run{T}"/> is under way, so the world stands still
/// while a test or a front end looks at it between operations. Work posted from other threads (a Ctrl+C, a test
/// thread) is taken in the order it arrives and counted in <see cref="ForeignPosts"/>.
/// </para>
/// </remarks>
public sealed class SimulationLoop : SynchronizationContext, IDisposable
{
    // A plain monitor rather than System.Threading.Lock: the loop waits on it with Monitor.Wait.
    private readonly object _lock = new();
    private readonly Queue<(SendOrPostCallback Callback, object? State)> _ready = new();
    private readonly TimerHeap _timers = new();
    private readonly List<Root> _roots = [];
    private readonly Thread _thread;
    private readonly LoopTaskScheduler _scheduler;
    private long _now;
    private long _sequence;
    private long _steps;
    private long _foreignPosts;
    private bool _stopping;
    private readonly bool _paced;
    private readonly TimeProvider _wall;
    private readonly long _wallStart;

    /// <param name="name">The loop thread's name.</param>
    /// <param name="paced">
    /// Never ahead of the wall clock: each event waits until its time has come on the wall clock too, and an operation
    /// waiting for work from another thread (a page's Pause, Resume) waits for it instead of counting as deadlocked. For
    /// a live view (the app): every event still happens at its exact virtual time, so timing is what the model says.
    /// </param>
    /// <param name="wallClock">The wall clock a paced loop keeps to (the system's by default; a fake one in tests).</param>
    public SimulationLoop(string name = "simulation", bool paced = false, TimeProvider? wallClock = null)
    {
        _paced = paced;
        _wall = wallClock ?? TimeProvider.System;
        _wallStart = _wall.GetTimestamp();
        _scheduler = new LoopTaskScheduler(this);
        _thread = new Thread(Loop) { IsBackground = true, Name = name };
        _thread.Start();
    }

    private long WallTicks => _wall.GetElapsedTime(_wallStart).Ticks;

    /// <summary>Virtual time since the loop started, in ticks of 100 ns.</summary>
    public long NowTicks => Volatile.Read(ref _now);

    /// <summary>Steps taken so far: work items run and timers fired.</summary>
    public long Steps => Interlocked.Read(ref _steps);

    /// <summary>Work posted from another thread while an operation was under way: each one is a place where the result could depend on thread timing.</summary>
    public long ForeignPosts => Interlocked.Read(ref _foreignPosts);

    /// <summary>Timers waiting to fire (a cancelled or disposed one is no longer among them).</summary>
    internal int PendingTimers
    {
        get
        {
            lock (_lock)
            {
                return _timers.Count;
            }
        }
    }

    /// <summary>Whether the caller is the loop's own thread.</summary>
    public bool IsOnLoop => Environment.CurrentManagedThreadId == _thread.ManagedThreadId;

    /// <summary>A task scheduler that runs tasks on the loop.</summary>
    public TaskScheduler Scheduler => _scheduler;

    /// <summary>Runs <paramref name="operation"/> on the loop; virtual time moves while it is under way.</summary>
    /// <param name="operation">The operation, started on the loop.</param>
    /// <param name="name">What it is, for a deadlock report.</param>
    public Task<T> Run<T>(Func<Task<T>> operation, string name = "operation")
    {
        ArgumentNullException.ThrowIfNull(operation);
        var root = new Root(name);
        var done = new TaskCompletionSource<T>(TaskCreationOptions.RunContinuationsAsynchronously);
        root.Fail = done.TrySetException;
        lock (_lock)
        {
            ObjectDisposedException.ThrowIf(_stopping, this);
            if (_paced && _roots.Count == 0)
            {
                // Virtual time stood still while nothing ran: an operation starts now on the wall clock too, or its first
                // seconds would race to catch up (a run after an idle minute ran 48 s of the machine's time in 1 s).
                _now = Math.Max(_now, WallTicks);
            }

            // The operation and its first step go in together: a loop that looked in between would see an operation with
            // nothing to do and report a deadlock (it happened at t = 0 when the loop's thread was slow to start).
            _roots.Add(root);
            Enqueue(_ => Start(), null, countForeign: false);
        }

        return done.Task;

        async void Start()
        {
            try
            {
                var result = await operation();
                Finish(root, () => done.TrySetResult(result));
            }
            catch (OperationCanceledException ex)
            {
                Finish(root, () => done.TrySetCanceled(ex.CancellationToken));
            }
            catch (Exception ex)
            {
                Finish(root, () => done.TrySetException(ex));
            }
        }
    }

    /// <summary>Starts <paramref name="work"/> on the loop without counting it as an operation (a reader loop, a device session).</summary>
    public Task Start(Func<Task> work)
    {
        ArgumentNullException.ThrowIfNull(work);
        return Task.Factory.StartNew(work, CancellationToken.None, TaskCreationOptions.DenyChildAttach, _scheduler).Unwrap();
    }

    public override void Post(SendOrPostCallback d, object? state)
    {
        ArgumentNullException.ThrowIfNull(d);
        Enqueue(d, state, countForeign: true);
    }

    public override void Send(SendOrPostCallback d, object? state)
    {
        if (!IsOnLoop)
        {
            throw new NotSupportedException("the simulation loop runs work only on its own thread: post it");
        }

        d(state);
    }

    public override SynchronizationContext CreateCopy() => this;

    /// <summary>Stops the loop thread once the work already queued has run; pending timers never fire.</summary>
    public void Dispose()
    {
        lock (_lock)
        {
            if (_stopping)
            {
                return;
            }

            _stopping = true;
            Monitor.PulseAll(_lock);
        }

        if (!IsOnLoop)
        {
            _thread.Join();
        }
    }

    internal LoopTimer CreateTimer(TimerCallback callback, object? state)
    {
        if (!IsOnLoop)
        {
            // A timer made elsewhere would start its wait at whatever virtual time the loop happens to be at.
            throw new InvalidOperationException("the simulation's clock was used off its loop: run the code through SimulationLoop.Run (or the machine's RunAsync)");
        }

        return new LoopTimer(this, callback, state);
    }

    internal void Change(LoopTimer timer, long dueTicks, long periodTicks)
    {
        lock (_lock)
        {
            timer.PeriodTicks = periodTicks > 0 ? periodTicks : 0;
            if (dueTicks >= 0 && !timer.Disposed)
            {
                _timers.Schedule(timer, _now + dueTicks, _sequence++);
            }
            else
            {
                _timers.Remove(timer);
            }
        }
    }

    internal void Remove(LoopTimer timer)
    {
        lock (_lock)
        {
            timer.Disposed = true;
            _timers.Remove(timer);
        }
    }

    private void Enqueue(SendOrPostCallback callback, object? state, bool countForeign)
    {
        var foreign = !IsOnLoop;
        lock (_lock)
        {
            _ready.Enqueue((callback, state));
            if (foreign)
            {
                if (countForeign && _roots.Count > 0)
                {
                    _foreignPosts++;
                }

                Monitor.Pulse(_lock);
            }
        }
    }

    private void Loop()
    {
        SetSynchronizationContext(this);
        while (true)
        {
            SendOrPostCallback? callback = null;
            object? state = null;
            LoopTimer? due = null;
            List<Root>? deadlocked = null;
            List<Root>? finished = null;
            lock (_lock)
            {
                while (true)
                {
                    if (_ready.TryDequeue(out var work))
                    {
                        (callback, state) = work;
                        break;
                    }

                    var head = _timers.Peek();
                    var hasTimer = head is not null;
                    var at = head?.Due ?? 0;
                    if (!(hasTimer && at <= _now) && _roots.Exists(r => r.Finished))
                    {
                        // Quiet at this instant: hand out finished operations before time moves on, so whoever waits
                        // for one sees the simulation standing still.
                        finished = _roots.FindAll(r => r.Finished);
                        _roots.RemoveAll(r => r.Finished);
                        break;
                    }

                    if (_paced && _roots.Count == 0)
                    {
                        // Idle: virtual time catches up with the wall clock, so the next operation starts now.
                        _now = Math.Max(_now, WallTicks);
                    }

                    if (_paced && hasTimer && at > _now && _roots.Count > 0 && WallTicks < at)
                    {
                        Monitor.Wait(_lock, TimeSpan.FromTicks(Math.Max(1, at - WallTicks)));
                        continue;
                    }

                    if (hasTimer && (at <= _now || _roots.Count > 0))
                    {
                        _now = Math.Max(_now, at);
                        due = head!;
                        if (due.PeriodTicks > 0)
                        {
                            _timers.Schedule(due, _now + due.PeriodTicks, _sequence++);
                        }
                        else
                        {
                            _timers.Remove(due);
                        }

                        break;
                    }

                    if (_roots.Count > 0 && _paced)
                    {
                        // Paced: what an operation waits for can come from another thread at any time.
                        Monitor.Wait(_lock);
                        continue;
                    }

                    if (_roots.Count > 0)
                    {
                        // Every operation left is unfinished (finished ones were handed out above).
                        deadlocked = [.. _roots];
                        _roots.Clear();
                        break;
                    }

                    if (_stopping)
                    {
                        return;
                    }

                    Monitor.Wait(_lock);
                }
            }

            _steps++;
            try
            {
                if (finished is not null)
                {
                    finished.ForEach(r => r.Complete!());
                }
                else if (deadlocked is not null)
                {
                    ReportDeadlock(deadlocked);
                }
                else if (due is not null)
                {
                    due.Fire();
                }
                else
                {
                    callback!(state);
                }
            }
            catch (Exception ex)
            {
                // An exception nobody awaits (an async void handler): it ends every operation under way rather than the process.
                FailAll(new InvalidOperationException($"unhandled in the simulation: {ex.Message}", ex));
            }
        }
    }

    // An operation that left the loop (ConfigureAwait(false) somewhere) finishes through a post, so the loop wakes to hand it out.
    private void Finish(Root root, Action complete)
    {
        if (IsOnLoop)
        {
            root.Finish(complete);
        }
        else
        {
            Enqueue(_ => root.Finish(complete), null, countForeign: true);
        }
    }

    private void FailAll(Exception error)
    {
        List<Root> roots;
        lock (_lock)
        {
            roots = [.. _roots];
            _roots.Clear();
        }

        foreach (var root in roots)
        {
            root.Fail!(error);
        }
    }

    private void ReportDeadlock(List<Root> roots)
    {
        var at = TimeSpan.FromTicks(_now).TotalSeconds.ToString("0.######", CultureInfo.InvariantCulture);
        var waiting = string.Join(", ", roots.Select(r => r.Name));
        var error = new SimulationDeadlockException($"simulation deadlock at t = {at} s: no work and no timer left while waiting for: {waiting}");
        foreach (var root in roots)
        {
            root.Fail!(error);
        }
    }

    private sealed class Root(string name)
    {
        public string Name { get; } = name;

        public Func<Exception, bool>? Fail { get; set; }

        // Written on the loop thread, read under the loop's lock by the same thread.
        public bool Finished { get; private set; }

        public Action? Complete { get; private set; }

        public void Finish(Action complete)
        {
            Complete = complete;
            Finished = true;
        }
    }

    private sealed class LoopTaskScheduler(SimulationLoop loop) : TaskScheduler
    {
        public override int MaximumConcurrencyLevel => 1;

        protected override void QueueTask(Task task) => loop.Post(static s => ((LoopTaskScheduler)((object[])s!)[0]).TryExecuteTask((Task)((object[])s!)[1]), new object[] { this, task });

        protected override bool TryExecuteTaskInline(Task task, bool taskWasPreviouslyQueued) => loop.IsOnLoop && TryExecuteTask(task);

        protected override IEnumerable<Task>? GetScheduledTasks() => null;
    }
}
