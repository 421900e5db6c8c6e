using LaserEngrave.Simulator.Timing;

namespace LaserEngrave.Simulator.Tests.Timing;

public class SimulationLoopTests
{
    [Fact(Timeout = 20_000)]
    public async Task Run_Delays_ResumeAtTheirVirtualTimesInOrder()
    {
        using var time = new VirtualTimeProvider();
        var log = new List<string>();

        await time.Run(async () =>
        {
            var slow = Step("slow", 30);
            var fast = Step("fast", 5);
            await Task.WhenAll(slow, fast);
            return true;
        });

        Assert.Equal(["fast at 5 ms", "slow at 30 ms"], log);

        async Task Step(string name, int ms)
        {
            await Task.Delay(TimeSpan.FromMilliseconds(ms), time);
            log.Add($"{name} at {time.Elapsed.TotalMilliseconds} ms");
        }
    }

    [Fact(Timeout = 20_000)]
    public async Task CreateTimer_KeepsWholeTicks_NotWholeMilliseconds()
    {
        using var time = new VirtualTimeProvider();

        var firedAt = await time.Run(async () =>
        {
            var fired = new TaskCompletionSource<TimeSpan>();
            using var timer = time.CreateTimer(_ => fired.TrySetResult(time.Elapsed), null, TimeSpan.FromTicks(62_500), Timeout.InfiniteTimeSpan);
            return await fired.Task;
        });

        Assert.Equal(TimeSpan.FromTicks(62_500), firedAt);
    }

    [Fact(Timeout = 20_000)]
    public async Task Run_CancellationAfterATimeout_FiresOnTheVirtualClock()
    {
        using var time = new VirtualTimeProvider();

        var (cancelledAt, onLoop) = await time.Run(async () =>
        {
            using var cts = new CancellationTokenSource(TimeSpan.FromSeconds(2), time);
            try
            {
                await Task.Delay(Timeout.InfiniteTimeSpan, time, cts.Token);
            }
            catch (OperationCanceledException)
            {
            }

            return (time.Elapsed, time.Loop.IsOnLoop);
        });

        Assert.Equal(TimeSpan.FromSeconds(2), cancelledAt);
        Assert.True(onLoop, "the continuation left the loop");
    }

    [Fact(Timeout = 20_000)]
    public async Task CreateTimer_CancelledOrDisposed_LeavesTheHeapAtOnce()
    {
        using var time = new VirtualTimeProvider();

        var (whileWaiting, afterwards) = await time.Run(async () =>
        {
            // A reply answered in time: its watch timer is cancelled long before it would fire.
            using (var watch = new CancellationTokenSource(TimeSpan.FromSeconds(10), time))
            {
                await Task.Delay(TimeSpan.FromMilliseconds(1), time);
            }

            var timer = time.CreateTimer(_ => { }, null, TimeSpan.FromSeconds(5), Timeout.InfiniteTimeSpan);
            var waiting = time.Loop.PendingTimers;
            timer.Change(Timeout.InfiniteTimeSpan, Timeout.InfiniteTimeSpan);
            var stopped = time.Loop.PendingTimers;
            timer.Change(TimeSpan.FromSeconds(1), Timeout.InfiniteTimeSpan);
            timer.Dispose();
            return (waiting, stopped + time.Loop.PendingTimers);
        });

        Assert.Equal(1, whileWaiting);
        Assert.Equal(0, afterwards);
    }

    [Fact(Timeout = 20_000)]
    public async Task CreateTimer_ChangedAndSameInstant_FireByTimeThenByWhenSet()
    {
        using var time = new VirtualTimeProvider();
        var log = new List<string>();

        await time.Run(async () =>
        {
            var done = new TaskCompletionSource();
            var timers = new List<ITimer>();
            foreach (var (name, ms) in new[] { ("a", 30), ("b", 10), ("c", 20), ("d", 10), ("e", 40) })
            {
                timers.Add(time.CreateTimer(_ => log.Add($"{name} {time.Elapsed.TotalMilliseconds}"), null, TimeSpan.FromMilliseconds(ms), Timeout.InfiniteTimeSpan));
            }

            // Moved: a to 10 ms, set after b and d, so it fires after them; c cancelled; e moved earlier, to 5 ms.
            timers[0].Change(TimeSpan.FromMilliseconds(10), Timeout.InfiniteTimeSpan);
            timers[2].Dispose();
            timers[4].Change(TimeSpan.FromMilliseconds(5), Timeout.InfiniteTimeSpan);
            using var end = time.CreateTimer(_ => done.TrySetResult(), null, TimeSpan.FromMilliseconds(50), Timeout.InfiniteTimeSpan);
            await done.Task;
            return true;
        });

        Assert.Equal(["e 5", "b 10", "d 10", "a 10"], log);
    }

    [Fact(Timeout = 20_000)]
    public async Task CreateTimer_Periodic_FiresEveryPeriodUntilDisposed()
    {
        using var time = new VirtualTimeProvider();
        var fired = new List<double>();

        var left = await time.Run(async () =>
        {
            ITimer? timer = null;
            var done = new TaskCompletionSource();
            timer = time.CreateTimer(
                _ =>
                {
                    fired.Add(time.Elapsed.TotalMilliseconds);
                    if (fired.Count == 3)
                    {
                        timer!.Dispose();
                        done.TrySetResult();
                    }
                },
                null,
                TimeSpan.FromMilliseconds(2),
                TimeSpan.FromMilliseconds(5));
            await done.Task;
            return time.Loop.PendingTimers;
        });

        Assert.Equal([2.0, 7.0, 12.0], fired);
        Assert.Equal(0, left);
    }

    [Fact(Timeout = 20_000)]
    public async Task Run_NothingLeftToWaitFor_ReportsADeadlockNamingTheOperation()
    {
        using var time = new VirtualTimeProvider();

        var error = await Assert.ThrowsAsync<SimulationDeadlockException>(() => time.Loop.Run(
            async () =>
            {
                await Task.Delay(TimeSpan.FromMilliseconds(40), time);
                return await new TaskCompletionSource<int>().Task;
            },
            "the reply nobody sends"));

        Assert.Equal("simulation deadlock at t = 0.04 s: no work and no timer left while waiting for: the reply nobody sends", error.Message);
    }

    [Fact(Timeout = 20_000)]
    public async Task Run_Paced_WaitsForWorkFromAnotherThreadInsteadOfReportingADeadlock()
    {
        using var time = new VirtualTimeProvider(paced: true);
        var resume = new TaskCompletionSource<int>(TaskCreationOptions.RunContinuationsAsynchronously);
        var ct = TestContext.Current.CancellationToken;
        _ = Task.Run(
            async () =>
            {
                await Task.Delay(50, ct);
                resume.TrySetResult(7);
            },
            ct);

        var value = await time.Loop.Run(
            async () =>
            {
                await Task.Delay(TimeSpan.FromMilliseconds(1), time);
                return await resume.Task;
            },
            "a resume from the page");

        Assert.Equal(7, value);
    }

    [Fact(Timeout = 20_000)]
    public async Task Run_Paced_NeverAheadOfTheWallClockAndEachEventAtItsExactTime()
    {
        // The wall clock's watch starts before the provider, whose pace counts from its creation.
        var wall = System.Diagnostics.Stopwatch.StartNew();
        using var time = new VirtualTimeProvider(paced: true);

        var (elapsed, at) = await time.Run(async () =>
        {
            var start = time.Elapsed;
            await Task.Delay(TimeSpan.FromMilliseconds(80), time);
            return (wall.Elapsed, time.Elapsed - start);
        });

        Assert.True(elapsed >= TimeSpan.FromMilliseconds(79), $"{elapsed}");
        Assert.Equal(TimeSpan.FromMilliseconds(80), at);
    }

    [Fact(Timeout = 20_000)]
    public async Task Run_PacedAfterIdle_StartsAtTheWallClocksTimeAndKeepsItsPace()
    {
        // The app's case: a run (aborted), the machine left idle 30 s, then the next run.
        var wall = new ManualWallClock();
        using var time = new VirtualTimeProvider(paced: true, wallClock: wall);
        Task? idle = null;
        await time.Run(() =>
        {
            idle = wall.NextRead();
            return Task.FromResult(0);
        });

        // The loop has looked at the wall clock once the run ended, and sleeps: then 30 s pass.
        await idle!;
        wall.Advance(TimeSpan.FromSeconds(30));

        var (start, end) = await time.Run(async () =>
        {
            var begun = time.Elapsed;

            // The wall clock passes the run's 2 s as the run does (the loop never waits: the clock is a fake).
            wall.Advance(TimeSpan.FromSeconds(2));
            await Task.Delay(TimeSpan.FromSeconds(2), time);
            return (begun, time.Elapsed);
        });

        // Not 0 and 2 s, 30 s behind the wall clock: the run's first 30 s of the machine's time would pass at once.
        Assert.Equal(TimeSpan.FromSeconds(30), start);
        Assert.Equal(TimeSpan.FromSeconds(32), end);
    }

    /// <summary>A wall clock the test moves by hand.</summary>
    private sealed class ManualWallClock : TimeProvider
    {
        private long _ticks;
        private TaskCompletionSource? _read;

        public override long TimestampFrequency => TimeSpan.TicksPerSecond;

        public override long GetTimestamp()
        {
            Interlocked.Exchange(ref _read, null)?.TrySetResult();
            return Interlocked.Read(ref _ticks);
        }

        /// <summary>Completes at the clock's next reading.</summary>
        public Task NextRead()
        {
            var read = new TaskCompletionSource(TaskCreationOptions.RunContinuationsAsynchronously);
            _read = read;
            return read.Task;
        }

        public override DateTimeOffset GetUtcNow() => DateTimeOffset.UnixEpoch + TimeSpan.FromTicks(GetTimestamp());

        public void Advance(TimeSpan by) => Interlocked.Add(ref _ticks, by.Ticks);
    }

    [Fact(Timeout = 20_000)]
    public async Task Time_BetweenOperations_StandsStill()
    {
        using var time = new VirtualTimeProvider();
        var ticks = 0;
        await time.Run(() =>
        {
            // A periodic timer that would run for ever if time moved on its own.
            time.CreateTimer(_ => ticks++, null, TimeSpan.FromMilliseconds(10), TimeSpan.FromMilliseconds(10));
            return Task.FromResult(true);
        });
        var after = time.Elapsed;

        await Task.Delay(50, TestContext.Current.CancellationToken);
        var during = await time.Run(async () =>
        {
            // 105 ms: the tenth tick (due at 100 ms) is behind the delay if both are due at the same instant.
            await Task.Delay(TimeSpan.FromMilliseconds(105), time);
            return ticks;
        });

        Assert.Equal(TimeSpan.Zero, after);
        Assert.Equal(10, during);
    }

    [Fact(Timeout = 20_000)]
    public async Task Run_FinishedOperation_IsHandedOutOnlyOnceTheInstantIsQuiet()
    {
        using var time = new VirtualTimeProvider();
        var late = false;

        await time.Run(async () =>
        {
            await Task.Delay(TimeSpan.FromMilliseconds(10), time);
            // Due at the same instant the operation ends: it runs before the caller sees the result.
            time.CreateTimer(_ => late = true, null, TimeSpan.Zero, Timeout.InfiniteTimeSpan);
            return true;
        });

        Assert.True(late);
    }

    [Fact(Timeout = 20_000)]
    public void CreateTimer_OffTheLoop_IsRefused()
    {
        using var time = new VirtualTimeProvider();

        var error = Assert.Throws<InvalidOperationException>(() => time.CreateTimer(_ => { }, null, TimeSpan.FromSeconds(1), Timeout.InfiniteTimeSpan));

        Assert.Contains("off its loop", error.Message, StringComparison.Ordinal);
    }

    [Fact(Timeout = 20_000)]
    public async Task Run_SameWork_TakesTheSameStepsAtTheSameTimes()
    {
        var first = await Trace(seed: 7);
        var second = await Trace(seed: 7);

        Assert.Equal(first, second);
        Assert.Contains("steps", first, StringComparison.Ordinal);

        static async Task<string> Trace(int seed)
        {
            using var time = new VirtualTimeProvider();
            var random = new Random(seed);
            var log = new List<string>();
            await time.Run(async () =>
            {
                var workers = Enumerable.Range(0, 20).Select(async i =>
                {
                    for (var k = 0; k < 50; k++)
                    {
                        await Task.Delay(TimeSpan.FromMilliseconds(random.Next(1, 20)), time);
                        log.Add($"{i}@{time.Elapsed.Ticks}");
                    }
                });
                await Task.WhenAll(workers);
                return true;
            });
            return $"{string.Join(",", log)} steps {time.Loop.Steps}";
        }
    }
}
