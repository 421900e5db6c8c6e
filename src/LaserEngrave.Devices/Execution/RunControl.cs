namespace LaserEngrave.Devices.Execution;

/// <summary>
/// The one record of a run's state: its phase, and what was asked of it, pause and abort (from any thread, at any time),
/// with the signal a paused run waits on. Each <see cref="RunExecutor"/> acts on it and moves its phase; an
/// <see cref="EngraveSession"/> hands the same one to every pass it runs and reads it, so a request made between passes
/// (or before the first) holds the next one, and the session's state is the one held here.
/// </summary>
/// <remarks>
/// Its lock is taken last (under an executor's or a session's, never the other way round). An abort asked here is
/// carried out by the executor that is told (<see cref="RunExecutor.Abort"/>): it sends the laser's switch-off first.
/// </remarks>
internal sealed class RunControl
{
    private readonly Lock _lock = new();
    private bool _pauseRequested;
    private bool _abortRequested;
    private RunState _phase = RunState.Idle;
    private TaskCompletionSource _resumed = NewSignal();

    /// <summary>
    /// The run's phase over all its passes: the state of the pass that runs (<see cref="Entered"/>), Aborting as soon as
    /// an abort is asked, and its end only once the whole run has ended (<see cref="End"/>), not when a pass does.
    /// </summary>
    public RunState Phase
    {
        get
        {
            lock (_lock)
            {
                return _phase;
            }
        }
    }

    public bool PauseRequested
    {
        get
        {
            lock (_lock)
            {
                return _pauseRequested;
            }
        }
    }

    public bool AbortRequested
    {
        get
        {
            lock (_lock)
            {
                return _abortRequested;
            }
        }
    }

    /// <summary>Asks for a pause unless an abort was asked; whether a pause is asked now.</summary>
    public bool RequestPause()
    {
        lock (_lock)
        {
            _pauseRequested |= !_abortRequested;
            return _pauseRequested;
        }
    }

    /// <summary>Withdraws a pause; the signal to set once the caller has updated its state, or null when none was asked.</summary>
    public TaskCompletionSource? RequestResume()
    {
        lock (_lock)
        {
            if (!_pauseRequested)
            {
                return null;
            }

            _pauseRequested = false;
            var resumed = _resumed;
            _resumed = NewSignal();
            return resumed;
        }
    }

    /// <summary>Records an abort (once), the phase Aborting at once; the signal that wakes a paused run, for the executor to set once its off sequence has started.</summary>
    public TaskCompletionSource RequestAbort()
    {
        lock (_lock)
        {
            _abortRequested = true;

            // Also between passes or before the first: the pass's own Aborting follows.
            if (RunStateMachine.IsLegal(_phase, RunState.Aborting))
            {
                _phase = RunState.Aborting;
            }

            return _resumed;
        }
    }

    /// <summary>
    /// A pass's executor entered <paramref name="state"/> along the state table: the run's phase follows it, except that a
    /// pass's end is not the run's (that comes once every pass has run), and once an abort is asked only Aborting counts.
    /// </summary>
    public void Entered(RunState state)
    {
        lock (_lock)
        {
            if (RunStateMachine.IsEnd(_phase) || RunStateMachine.IsEnd(state) || (_abortRequested && state is not RunState.Aborting))
            {
                return;
            }

            _phase = state;
        }
    }

    /// <summary>The whole run has ended (every pass run, the log written): its phase is <paramref name="end"/> for good.</summary>
    public void End(RunState end)
    {
        lock (_lock)
        {
            _phase = end;
        }
    }

    /// <summary>The signal a paused run waits on, or null when no pause is asked.</summary>
    public TaskCompletionSource? PauseSignal()
    {
        lock (_lock)
        {
            return _pauseRequested ? _resumed : null;
        }
    }

    private static TaskCompletionSource NewSignal() => new(TaskCreationOptions.RunContinuationsAsynchronously);
}
