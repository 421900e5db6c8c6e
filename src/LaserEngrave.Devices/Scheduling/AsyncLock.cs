namespace LaserEngrave.Devices.Scheduling;

/// <summary>A first-come first-served async lock whose waiters resume on their own scheduler.</summary>
/// <remarks>
/// Written by hand because <see cref="SemaphoreSlim.WaitAsync(CancellationToken)"/> with a cancellable token resumes a
/// contended waiter on the thread pool, which leaves the simulation's loop (docs/simulator.md). Here a waiter awaits its
/// own completion source directly, and cancellation completes that source.
/// </remarks>
public sealed class AsyncLock
{
    private readonly Lock _sync = new();
    private readonly LinkedList<TaskCompletionSource> _waiters = new();
    private bool _held;

    /// <summary>Waits until the lock is free and takes it; <see cref="Release"/> gives it to the next waiter.</summary>
    public async Task WaitAsync(CancellationToken cancellationToken = default)
    {
        cancellationToken.ThrowIfCancellationRequested();
        LinkedListNode<TaskCompletionSource> node;
        lock (_sync)
        {
            if (!_held)
            {
                _held = true;
                return;
            }

            node = _waiters.AddLast(new TaskCompletionSource(TaskCreationOptions.RunContinuationsAsynchronously));
        }

        await using var registration = cancellationToken.Register(() =>
        {
            lock (_sync)
            {
                if (node.List is null)
                {
                    // Already handed the lock: the waiter owns it and will release it.
                    return;
                }

                _waiters.Remove(node);
            }

            node.Value.TrySetCanceled(cancellationToken);
        });
        await node.Value.Task;
    }

    /// <summary>Hands the lock to the longest waiter, or frees it.</summary>
    public void Release()
    {
        TaskCompletionSource next;
        lock (_sync)
        {
            if (!_held)
            {
                throw new InvalidOperationException("the lock is not held");
            }

            if (_waiters.First is not { } first)
            {
                _held = false;
                return;
            }

            _waiters.RemoveFirst();
            next = first.Value;
        }

        next.TrySetResult();
    }
}
