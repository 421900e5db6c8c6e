using System.Diagnostics;
using LaserEngrave.Simulator.Timing;

namespace LaserEngrave.Simulator.Tests.Timing;

/// <summary>The simulator on the wall clock: events in the order of their instants, and each acting as of its instant.</summary>
/// <remarks>Nothing here depends on how late the computer runs an event: only on order and on the instants themselves.</remarks>
public class WallClockTests
{
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
