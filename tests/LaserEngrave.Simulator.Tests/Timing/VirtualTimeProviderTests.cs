using LaserEngrave.Simulator.Timing;

namespace LaserEngrave.Simulator.Tests.Timing;

public class VirtualTimeProviderTests
{
    private static readonly CancellationToken None = CancellationToken.None;

    [Fact(Timeout = 10_000)]
    public async Task Delay_OneHour_CompletesAtOneHourOfVirtualTime()
    {
        using var time = new VirtualTimeProvider();
        var start = time.GetTimestamp();

        await Task.Delay(TimeSpan.FromHours(1), time, None);

        Assert.Equal(TimeSpan.FromHours(1), time.GetElapsedTime(start));
    }

    [Fact(Timeout = 10_000)]
    public async Task Delay_SeveralStartedTogether_CompleteInVirtualTimeOrder()
    {
        using var time = new VirtualTimeProvider();
        var order = new List<int>();
        var delaysMs = new[] { 300, 100, 500, 200, 400 };

        await Task.WhenAll(delaysMs.Select(async ms =>
        {
            await Task.Delay(TimeSpan.FromMilliseconds(ms), time, None);
            lock (order)
            {
                order.Add(ms);
            }
        }));

        Assert.Equal(delaysMs.Order(), order);
        Assert.Equal(TimeSpan.FromMilliseconds(500), time.Elapsed);
    }

    [Fact(Timeout = 10_000)]
    public async Task CreateTimer_Chained_AddsUpToTheTick()
    {
        using var time = new VirtualTimeProvider();

        // One Zaber frame at 9600 baud is 62 500 ticks; Task.Delay itself works in whole milliseconds, timers do not.
        for (var i = 0; i < 20; i++)
        {
            var fired = new TaskCompletionSource();
            using var timer = time.CreateTimer(_ => fired.SetResult(), null, TimeSpan.FromTicks(62_500), Timeout.InfiniteTimeSpan);
            await fired.Task;
        }

        Assert.Equal(TimeSpan.FromMilliseconds(125), time.Elapsed);
    }

    [Fact(Timeout = 10_000)]
    public async Task WaitAsync_NothingElseHappens_TimeoutFires()
    {
        using var time = new VirtualTimeProvider();
        var never = new TaskCompletionSource();

        await Assert.ThrowsAsync<TimeoutException>(() => never.Task.WaitAsync(TimeSpan.FromSeconds(30), time, None));

        Assert.Equal(TimeSpan.FromSeconds(30), time.Elapsed);
    }

    [Fact(Timeout = 10_000)]
    public async Task WaitAsync_TaskDoneBeforeTimeout_TimeStopsAtTheTask()
    {
        using var time = new VirtualTimeProvider();
        var work = Task.Delay(TimeSpan.FromSeconds(2), time, None);

        await work.WaitAsync(TimeSpan.FromSeconds(30), time, None);

        Assert.Equal(TimeSpan.FromSeconds(2), time.Elapsed);
    }

    [Fact(Timeout = 10_000)]
    public async Task CancellationTokenSource_WithTimeout_CancelsAtVirtualTime()
    {
        using var time = new VirtualTimeProvider();
        using var cts = new CancellationTokenSource(TimeSpan.FromMinutes(5), time);
        var cancelledAt = new TaskCompletionSource<TimeSpan>();
        using var registration = cts.Token.Register(() => cancelledAt.TrySetResult(time.Elapsed));

        var at = await cancelledAt.Task;

        Assert.Equal(TimeSpan.FromMinutes(5), at);
    }

    [Fact(Timeout = 10_000)]
    public async Task CancellationTokenSource_CancelAfter_MovesTheDeadline()
    {
        using var time = new VirtualTimeProvider();
        using var cts = new CancellationTokenSource(TimeSpan.FromMinutes(5), time);
        cts.CancelAfter(TimeSpan.FromSeconds(7));

        await Assert.ThrowsAnyAsync<OperationCanceledException>(() => Task.Delay(Timeout.InfiniteTimeSpan, time, cts.Token));

        Assert.Equal(TimeSpan.FromSeconds(7), time.Elapsed);
    }

    [Fact(Timeout = 10_000)]
    public async Task Delay_Cancelled_DoesNotAdvanceToItsDueTime()
    {
        using var time = new VirtualTimeProvider();
        using var cts = new CancellationTokenSource();
        var longDelay = Task.Delay(TimeSpan.FromHours(10), time, cts.Token);
        await cts.CancelAsync();
        await Assert.ThrowsAnyAsync<OperationCanceledException>(() => longDelay);

        await Task.Delay(TimeSpan.FromSeconds(1), time, None);

        Assert.Equal(TimeSpan.FromSeconds(1), time.Elapsed);
        Assert.Equal(0, time.PendingTimers);
    }

    [Fact(Timeout = 10_000)]
    public async Task GetUtcNow_FollowsVirtualTime()
    {
        var start = new DateTimeOffset(2030, 1, 2, 3, 4, 5, TimeSpan.Zero);
        using var time = new VirtualTimeProvider(start);

        await Task.Delay(TimeSpan.FromMinutes(90), time, None);

        Assert.Equal(start.AddMinutes(90), time.GetUtcNow());
    }

    [Fact]
    public void GetTimestamp_NoTimers_TimeStandsStill()
    {
        using var time = new VirtualTimeProvider();
        var before = time.GetTimestamp();

        Thread.Sleep(20);

        Assert.Equal(before, time.GetTimestamp());
    }

    [Fact(Timeout = 10_000)]
    public async Task CreateTimer_Periodic_FiresEveryPeriod()
    {
        using var time = new VirtualTimeProvider();
        var ticks = new List<TimeSpan>();
        var fifth = new TaskCompletionSource();
        using var timer = time.CreateTimer(
            _ =>
            {
                lock (ticks)
                {
                    ticks.Add(time.Elapsed);
                    if (ticks.Count == 5)
                    {
                        fifth.TrySetResult();
                    }
                }
            },
            null,
            TimeSpan.FromMilliseconds(100),
            TimeSpan.FromMilliseconds(250));

        await fifth.Task;
        timer.Dispose();

        Assert.Equal([100, 350, 600, 850, 1100], ticks.Take(5).Select(t => t.TotalMilliseconds));
    }

    [Fact(Timeout = 10_000)]
    public async Task CreateTimer_ChangedToLater_FiresOnlyAtTheNewTime()
    {
        using var time = new VirtualTimeProvider();
        var fired = new TaskCompletionSource<TimeSpan>();
        using var timer = time.CreateTimer(_ => fired.TrySetResult(time.Elapsed), null, Timeout.InfiniteTimeSpan, Timeout.InfiniteTimeSpan);

        timer.Change(TimeSpan.FromSeconds(1), Timeout.InfiniteTimeSpan);
        timer.Change(TimeSpan.FromSeconds(3), Timeout.InfiniteTimeSpan);

        Assert.Equal(TimeSpan.FromSeconds(3), await fired.Task);
    }

    [Fact(Timeout = 10_000)]
    public async Task CreateTimer_Disposed_NeverFires()
    {
        using var time = new VirtualTimeProvider();
        var fired = false;
        var timer = time.CreateTimer(_ => fired = true, null, TimeSpan.FromSeconds(1), Timeout.InfiniteTimeSpan);
        timer.Dispose();

        await Task.Delay(TimeSpan.FromSeconds(2), time, None);

        Assert.False(fired);
        Assert.False(timer.Change(TimeSpan.FromSeconds(1), Timeout.InfiniteTimeSpan));
    }

    [Fact(Timeout = 10_000)]
    public async Task Hold_Kept_ClockStandsStillUntilReleased()
    {
        using var time = new VirtualTimeProvider();
        var hold = time.Hold();
        var delay = Task.Delay(TimeSpan.FromSeconds(1), time, None);

        Thread.Sleep(50);

        Assert.False(delay.IsCompleted);
        Assert.Equal(TimeSpan.Zero, time.Elapsed);
        hold.Dispose();
        await delay;
        Assert.Equal(TimeSpan.FromSeconds(1), time.Elapsed);
    }

    [Fact(Timeout = 10_000)]
    public async Task Hold_ForgottenPastTheLimit_NoLongerHoldsTheClock()
    {
        using var time = new VirtualTimeProvider();
        _ = time.Hold();

        await Task.Delay(TimeSpan.FromSeconds(1), time, None);

        Assert.Equal(TimeSpan.FromSeconds(1), time.Elapsed);
    }

    [Fact(Timeout = 10_000)]
    public async Task TimerCallback_StillRunning_HoldsTheClock()
    {
        using var time = new VirtualTimeProvider();
        var seenInCallback = TimeSpan.Zero;
        var done = new TaskCompletionSource();
        using var first = time.CreateTimer(
            _ =>
            {
                // Busy for a while (wall clock) without touching the clock: the later timer must wait for it.
                Thread.Sleep(50);
                seenInCallback = time.Elapsed;
                done.TrySetResult();
            },
            null,
            TimeSpan.FromSeconds(1),
            Timeout.InfiniteTimeSpan);
        var later = Task.Delay(TimeSpan.FromSeconds(2), time, None);

        await done.Task;

        Assert.Equal(TimeSpan.FromSeconds(1), seenInCallback);
        await later;
    }

    [Fact(Timeout = 10_000)]
    public async Task Delay_ManyConcurrentChains_EachSeesItsOwnTimes()
    {
        using var time = new VirtualTimeProvider();

        async Task<bool> Chain(int periodMs)
        {
            var start = time.GetTimestamp();
            for (var i = 1; i <= 10; i++)
            {
                await Task.Delay(TimeSpan.FromMilliseconds(periodMs), time, None);
                if (time.GetElapsedTime(start) != TimeSpan.FromMilliseconds(periodMs * i))
                {
                    return false;
                }
            }

            return true;
        }

        var results = await Task.WhenAll(Enumerable.Range(1, 8).Select(k => Chain(k * 7)));

        Assert.All(results, Assert.True);
    }

    [Fact]
    public void CreateTimer_NegativeDueTime_Throws()
    {
        using var time = new VirtualTimeProvider();

        Assert.Throws<ArgumentOutOfRangeException>(() => time.CreateTimer(_ => { }, null, TimeSpan.FromSeconds(-1), Timeout.InfiniteTimeSpan));
    }

    [Fact]
    public void CreateTimer_DueTimeBeyondTheSystemLimit_Throws()
    {
        using var time = new VirtualTimeProvider();

        Assert.Throws<ArgumentOutOfRangeException>(() => time.CreateTimer(_ => { }, null, TimeSpan.MaxValue, Timeout.InfiniteTimeSpan));
        Assert.Throws<ArgumentOutOfRangeException>(() => time.CreateTimer(_ => { }, null, TimeSpan.FromSeconds(1), TimeSpan.FromDays(50)));
    }
}
