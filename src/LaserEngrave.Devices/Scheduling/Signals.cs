namespace LaserEngrave.Devices.Scheduling;

/// <summary>Waits for a reply or a signal with a timeout and cancellation, without leaving the caller's scheduler.</summary>
/// <remarks>
/// <c>Task.WaitAsync(timeout, timeProvider)</c> on a task whose continuations run asynchronously completes through the
/// thread pool, so in the simulation the loop could jump its clock to the timeout while the reply sits on another thread
/// (docs/simulator.md). Here the timer and the cancellation complete the awaited source themselves, on whichever
/// thread fires them (the loop's, in the simulation), and the caller awaits that source directly.
/// </remarks>
public static class Signals
{
    /// <summary>Waits for <paramref name="source"/>; a <see cref="TimeoutException"/> after <paramref name="timeout"/> (infinite: none).</summary>
    /// <remarks>The timeout and the cancellation complete <paramref name="source"/> itself: the caller owns it and expects no later result.</remarks>
    public static async Task<T> WaitAsync<T>(TaskCompletionSource<T> source, TimeSpan timeout, TimeProvider time, CancellationToken cancellationToken)
    {
        ArgumentNullException.ThrowIfNull(source);
        ArgumentNullException.ThrowIfNull(time);
        if (source.Task.IsCompleted)
        {
            return await source.Task;
        }

        ITimer? timer = null;
        if (timeout != Timeout.InfiniteTimeSpan)
        {
            timer = time.CreateTimer(static s => ((TaskCompletionSource<T>)s!).TrySetException(new TimeoutException()), source, timeout, Timeout.InfiniteTimeSpan);
        }

        try
        {
            await using var registration = cancellationToken.Register(static (s, token) => ((TaskCompletionSource<T>)s!).TrySetCanceled(token), source);
            return await source.Task;
        }
        finally
        {
            timer?.Dispose();
        }
    }

    /// <summary>Waits for <paramref name="source"/> or the cancellation of <paramref name="cancellationToken"/>, which cancels the source.</summary>
    public static async Task WaitAsync(TaskCompletionSource source, CancellationToken cancellationToken)
    {
        ArgumentNullException.ThrowIfNull(source);
        await using var registration = cancellationToken.Register(static (s, token) => ((TaskCompletionSource)s!).TrySetCanceled(token), source);
        await source.Task;
    }
}
