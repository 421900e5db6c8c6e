using System.Diagnostics;
using LaserEngrave.Wire.Scheduling;

namespace LaserEngrave.Wire.Tests.Scheduling;

/// <summary>The wall clock's pacer and the precise wait built on it: order, cancellation, never early.</summary>
/// <remarks>Nothing here depends on how late the computer runs an action: only on order and on the instants themselves.</remarks>
public class WallClockPacerTests
{
    [Fact(Timeout = 20_000)]
    public async Task Schedule_ActionsRunInTheOrderOfTheirInstants_TiesInTheOrderGiven()
    {
        var ms = Stopwatch.Frequency / 1000;
        var ran = new List<string>();
        var last = new TaskCompletionSource(TaskCreationOptions.RunContinuationsAsynchronously);
        var pacer = WallClockPacer.Shared;

        // The pacer's thread is held until every action is given, so a slow test thread cannot change their order.
        using var held = new ManualResetEventSlim();
        var now = Stopwatch.GetTimestamp();
        pacer.Schedule(now, () => held.Wait());
        pacer.Schedule(now + (30 * ms), () => ran.Add("30"));
        pacer.Schedule(now + (10 * ms), () => ran.Add("10 first"));
        pacer.Schedule(now + (20 * ms), () => ran.Add("20"));
        pacer.Schedule(now + (10 * ms), () => ran.Add("10 second"));
        pacer.Schedule(now + (40 * ms), () =>
        {
            ran.Add("40");
            last.SetResult();
        });
        held.Set();
        await last.Task;

        Assert.Equal(["10 first", "10 second", "20", "30", "40"], ran);
    }

    [Fact(Timeout = 20_000)]
    public async Task Schedule_CancelledAction_NeverRuns()
    {
        var ms = Stopwatch.Frequency / 1000;
        var ran = new List<string>();
        var last = new TaskCompletionSource(TaskCreationOptions.RunContinuationsAsynchronously);

        using var held = new ManualResetEventSlim();
        var now = Stopwatch.GetTimestamp();
        WallClockPacer.Shared.Schedule(now, () => held.Wait());
        var cancelled = WallClockPacer.Shared.Schedule(now + (10 * ms), () => ran.Add("cancelled"));
        WallClockPacer.Shared.Schedule(now + (20 * ms), () =>
        {
            ran.Add("kept");
            last.SetResult();
        });
        cancelled.Dispose();
        held.Set();
        await last.Task;

        Assert.Equal(["kept"], ran);
    }

    [Fact(Timeout = 20_000)]
    public async Task PreciseDelay_OnTheSystemClock_NeverEndsEarly()
    {
        var ct = TestContext.Current.CancellationToken;
        foreach (var us in new[] { 300, 1_500, 2_500, 17_000 })
        {
            var delay = TimeSpan.FromTicks(us * 10L);
            var start = Stopwatch.GetTimestamp();
            await PreciseDelay.DelayAsync(TimeProvider.System, delay, ct);
            Assert.True(Stopwatch.GetElapsedTime(start) >= delay, $"a wait of {us} µs ended after {Stopwatch.GetElapsedTime(start).TotalMicroseconds:0} µs");
        }
    }

    [Fact(Timeout = 20_000)]
    public async Task PreciseDelay_OnTheSystemClock_Cancelled_EndsCancelled()
    {
        using var cancel = new CancellationTokenSource();
        var wait = PreciseDelay.DelayAsync(TimeProvider.System, TimeSpan.FromHours(1), cancel.Token);
        Assert.False(wait.IsCompleted);

        cancel.Cancel();

        await Assert.ThrowsAnyAsync<OperationCanceledException>(() => wait);
    }
}
