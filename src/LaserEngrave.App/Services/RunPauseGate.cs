namespace LaserEngrave.App.Services;

/// <summary>Lets a run be held between moves (laser off) and released again.</summary>
public sealed class RunPauseGate
{
    private readonly Lock _lock = new();
    private TaskCompletionSource? _paused;

    /// <summary>Raised on every pause (true) and resume (false), for an executor with its own pause.</summary>
    public event EventHandler<bool>? Changed;

    public bool IsPaused
    {
        get
        {
            lock (_lock)
            {
                return _paused is not null;
            }
        }
    }

    public void Pause()
    {
        lock (_lock)
        {
            _paused ??= new TaskCompletionSource(TaskCreationOptions.RunContinuationsAsynchronously);
        }

        Changed?.Invoke(this, true);
    }

    public void Resume()
    {
        TaskCompletionSource? paused;
        lock (_lock)
        {
            paused = _paused;
            _paused = null;
        }

        paused?.TrySetResult();
        Changed?.Invoke(this, false);
    }

    /// <summary>Completes at once when not paused, otherwise when resumed (or cancelled).</summary>
    public Task WaitAsync(CancellationToken cancellationToken)
    {
        lock (_lock)
        {
            return _paused is null ? Task.CompletedTask : _paused.Task.WaitAsync(cancellationToken);
        }
    }
}
