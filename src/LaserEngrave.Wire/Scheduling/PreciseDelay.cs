using System.Diagnostics;

namespace LaserEngrave.Wire.Scheduling;

/// <summary>Waits to the tick on a <see cref="TimeProvider"/>: what timed laser switching needs.</summary>
/// <remarks>
/// Written by hand because <c>Task.Delay(TimeSpan, TimeProvider)</c> truncates the delay to whole milliseconds, a
/// micrometre at 1 mm/s. On a virtual clock the timer is created with the exact delay. On the system clock, whose timers
/// fire late by up to a scheduler tick (15.6 ms on Windows by default), the wait is the <see cref="WallClockPacer"/>'s,
/// which sleeps until 2 ms before the time (17 ms on Windows) and spins the rest on the high-resolution timestamp.
/// </remarks>
public static class PreciseDelay
{
    public static Task DelayAsync(TimeProvider time, TimeSpan delay, CancellationToken cancellationToken)
    {
        ArgumentNullException.ThrowIfNull(time);
        if (delay <= TimeSpan.Zero)
        {
            cancellationToken.ThrowIfCancellationRequested();
            return Task.CompletedTask;
        }

        if (time == TimeProvider.System)
        {
            return SystemDelayAsync(delay, cancellationToken);
        }

        // A simulated host wakes as late as its model says (a loaded computer); its code then reads the late time as it would.
        var late = time is IHostLateness host ? host.NextLateness() : TimeSpan.Zero;
        return TimerDelayAsync(time, late > TimeSpan.Zero ? delay + late : delay, cancellationToken);
    }

    // The continuation runs on the pacer's thread, at once: a hop to the thread pool would add its own lateness to the
    // command the caller sends next.
    private static async Task SystemDelayAsync(TimeSpan delay, CancellationToken cancellationToken)
    {
        var done = new TaskCompletionSource();
        var until = Stopwatch.GetTimestamp() + (long)(delay.TotalSeconds * Stopwatch.Frequency);
        using var scheduled = WallClockPacer.Shared.Schedule(until, () => done.TrySetResult());
        await using var registration = cancellationToken.UnsafeRegister(static (state, token) => ((TaskCompletionSource)state!).TrySetCanceled(token), done);
        await done.Task.ConfigureAwait(false);
    }

    private static Task TimerDelayAsync(TimeProvider time, TimeSpan delay, CancellationToken cancellationToken) =>
        new TimerDelay(time, delay, cancellationToken).Task;

    // Everything happens in the timer's or the token's callback, on whatever thread the clock runs them: nothing is
    // posted to the thread pool, which a simulation loop would not see. So the task's continuations run there too, at
    // once: with RunContinuationsAsynchronously a Task.WhenAny over this wait completed on the thread pool, and the loop,
    // seeing no work left, moved its clock on meanwhile. A deadline (the position query's before a switch-on) then ended
    // as late as the next event: 157 ms, by which time the query had answered, and the laser came on past its edge.
    private sealed class TimerDelay
    {
        private readonly TaskCompletionSource _done = new();
        private readonly ITimer _timer;
        private readonly CancellationTokenRegistration _registration;

        public TimerDelay(TimeProvider time, TimeSpan delay, CancellationToken cancellationToken)
        {
            _timer = time.CreateTimer(static state => ((TimerDelay)state!).Fire(), this, delay, Timeout.InfiniteTimeSpan);
            if (cancellationToken.CanBeCanceled)
            {
                _registration = cancellationToken.UnsafeRegister(static (state, token) => ((TimerDelay)state!).Cancel(token), this);
            }
        }

        public Task Task => _done.Task;

        private void Fire()
        {
            _registration.Dispose();
            _timer.Dispose();
            _done.TrySetResult();
        }

        private void Cancel(CancellationToken token)
        {
            _timer.Dispose();
            _done.TrySetCanceled(token);
        }
    }
}
