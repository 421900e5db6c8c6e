using System.Diagnostics;
using LaserEngrave.Simulator.Timing;

namespace LaserEngrave.Simulator.Tests.Timing;

/// <summary>The simulator on the wall clock: events in the order of their instants, and each acting as of its instant.</summary>
/// <remarks>Nothing here depends on how late the computer runs an event: only on order and on the instants themselves.</remarks>
public class WallClockTests
{
    [Fact(Timeout = 20_000)]
    public async Task Pacer_Events_RunInTheOrderOfTheirInstants_TiesInTheOrderGiven()
    {
        var now = Stopwatch.GetTimestamp();
        var ms = Stopwatch.Frequency / 1000;
        var ran = new List<string>();
        var last = new TaskCompletionSource(TaskCreationOptions.RunContinuationsAsynchronously);
        var pacer = WallClockPacer.Shared;

        pacer.Schedule(now + (30 * ms), () => ran.Add("30"));
        pacer.Schedule(now + (10 * ms), () => ran.Add("10 first"));
        pacer.Schedule(now + (20 * ms), () => ran.Add("20"));
        pacer.Schedule(now + (10 * ms), () => ran.Add("10 second"));
        pacer.Schedule(now + (40 * ms), () =>
        {
            ran.Add("40");
            last.SetResult();
        });
        await last.Task;

        Assert.Equal(["10 first", "10 second", "20", "30", "40"], ran);
    }

    [Fact(Timeout = 20_000)]
    public async Task Pacer_CancelledEvent_NeverRuns()
    {
        var now = Stopwatch.GetTimestamp();
        var ms = Stopwatch.Frequency / 1000;
        var ran = new List<string>();
        var last = new TaskCompletionSource(TaskCreationOptions.RunContinuationsAsynchronously);

        var cancelled = WallClockPacer.Shared.Schedule(now + (10 * ms), () => ran.Add("cancelled"));
        WallClockPacer.Shared.Schedule(now + (20 * ms), () =>
        {
            ran.Add("kept");
            last.SetResult();
        });
        cancelled.Dispose();
        await last.Task;

        Assert.Equal(["kept"], ran);
    }

    [Fact(Timeout = 20_000)]
    public async Task At_OnTheWallClock_TheEventReadsItsOwnInstant_NotWhenTheProcessGotToIt()
    {
        var clock = new SimulationClock(TimeProvider.System);
        var seen = new TaskCompletionSource<(double At, double Read)>(TaskCreationOptions.RunContinuationsAsynchronously);
        var at = clock.NowSeconds + 0.005;

        using var timer = clock.At(at, () => seen.SetResult((at, clock.NowSeconds)));
        var (instant, read) = await seen.Task;

        // However late the thread ran it, the event acts as of its instant (a position read, a reply's departure).
        Assert.Equal(instant, read);
        Assert.True(clock.NowSeconds >= instant);
    }

    [Fact(Timeout = 20_000)]
    public async Task RunAt_InVirtualTime_ChangesNothing_TheClockIsAtTheInstantAlready()
    {
        using var time = new VirtualTimeProvider();
        var clock = await time.Run(() => Task.FromResult(new SimulationClock(time)));

        var (before, inside) = await time.Run(async () =>
        {
            await Task.Delay(TimeSpan.FromMilliseconds(7), time);
            var read = double.NaN;
            clock.RunAt(0.001, () => read = clock.NowSeconds);
            return (clock.NowSeconds, read);
        });

        Assert.Equal(before, inside);
        Assert.Equal(0.007, inside, 9);
    }
}
