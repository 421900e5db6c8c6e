namespace LaserEngrave.Devices.Execution;

/// <summary>
/// The one record of what was asked of a run: pause and abort (from any thread, at any time), and the signal a paused
/// run waits on. Each <see cref="RunExecutor"/> acts on it; an <see cref="EngraveSession"/> hands the same one to every
/// pass it runs and only mirrors it, so a request made between passes (or before the first) holds the next one.
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
    private TaskCompletionSource _resumed = NewSignal();

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

    /// <summary>Records an abort (once); the signal that wakes a paused run, for the executor to set once its off sequence has started.</summary>
    public TaskCompletionSource RequestAbort()
    {
        lock (_lock)
        {
            _abortRequested = true;
            return _resumed;
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
