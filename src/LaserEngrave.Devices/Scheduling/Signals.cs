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
    /// <summary>How often a wait whose time is up looks again while its answer is still arriving.</summary>
    internal static readonly TimeSpan ArrivingRecheck = TimeSpan.FromMilliseconds(5);

    /// <summary>Waits for <paramref name="source"/>; a <see cref="TimeoutException"/> after <paramref name="timeout"/> (infinite: none).</summary>
    /// <remarks>The timeout and the cancellation complete <paramref name="source"/> itself: the caller owns it and expects no later result.</remarks>
    public static Task<T> WaitAsync<T>(TaskCompletionSource<T> source, TimeSpan timeout, TimeProvider time, CancellationToken cancellationToken) =>
        WaitAsync(source, timeout, time, null, cancellationToken);

    /// <summary>Waits for <paramref name="source"/>; a <see cref="TimeoutException"/> after <paramref name="timeout"/>, unless its answer is still arriving.</summary>
    /// <param name="source">What is awaited; the timeout and the cancellation complete it.</param>
    /// <param name="timeout">How long to wait (infinite: no timeout).</param>
    /// <param name="time">The clock.</param>
    /// <param name="arriving">
    /// Asked when the time is up: true while bytes that arrived are still being read or handed on (the host was slow to
    /// notice a reply, not the device to send it). The wait then looks again every few milliseconds, for at most one more
    /// <paramref name="timeout"/>. Null: none.
    /// </param>
    /// <param name="cancellationToken">Cancels the wait.</param>
    public static async Task<T> WaitAsync<T>(TaskCompletionSource<T> source, TimeSpan timeout, TimeProvider time, Func<bool>? arriving, CancellationToken cancellationToken)
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
            var deadline = new Deadline<T>(source, arriving, timeout);
            timer = time.CreateTimer(static s => ((Deadline<T>)s!).Expire(), deadline, timeout, Timeout.InfiniteTimeSpan);
            deadline.Timer = timer;
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

    private sealed class Deadline<T>(TaskCompletionSource<T> source, Func<bool>? arriving, TimeSpan grace)
    {
        private TimeSpan _extended;

        public ITimer? Timer { get; set; }

        public void Expire()
        {
            if (source.Task.IsCompleted)
            {
                return;
            }

            if (arriving is not null && _extended < grace && Timer is { } timer && arriving())
            {
                _extended += ArrivingRecheck;
                timer.Change(ArrivingRecheck, Timeout.InfiniteTimeSpan);
                return;
            }

            source.TrySetException(new TimeoutException());
        }
    }
}
