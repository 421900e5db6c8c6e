namespace LaserEngrave.App.Services;

/// <summary>Lets a run be held between moves (laser off) and released again.</summary>
public sealed class RunPauseGate
{
    private readonly Lock _lock = new();
    private TaskCompletionSource? _paused;

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
