using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Imaging;
using LaserEngrave.Core.Motion;
using LaserEngrave.Core.Planning;

namespace LaserEngrave.Core.Tests.Planning;

/// <summary>
/// The fast paths of planning and the estimate (remembered gap answers, a reused stroke plan, replies kept sorted, the
/// device-ramp check without a square root, word scans) against plain reference implementations, on seeded random input.
/// </summary>
public class PlanFastPathTests
{
    [Fact]
    public void GapMemo_RandomLengthsOnFourThreads_EqualTheFunction()
    {
        static double F(long length) => Math.Sqrt(Math.Abs(length)) + (length % 7);
        var memo = new GapMemo<double>(F);
        var rng = new Random(31);
        var lengths = Enumerable.Range(0, 20_000).Select(_ => rng.Next(5) switch
        {
            0 => rng.NextInt64(-5, 5),
            1 => GapMemo<double>.MaxLength + rng.NextInt64(-3, 3),
            2 => (rng.NextInt64(0, 1 << 14) << 10) + rng.NextInt64(-1, 2),
            _ => rng.NextInt64(0, 5000),
        }).ToArray();

        // Every thread reads the same lengths, so pages and values are filled in every order; each answer is the function's.
        var mismatches = new int[4];
        Parallel.For(0, 4, t =>
        {
            foreach (var length in t % 2 == 0 ? lengths : Enumerable.Reverse(lengths))
            {
                if (BitConverter.DoubleToInt64Bits(memo.Get(length)) != BitConverter.DoubleToInt64Bits(F(length)))
                {
                    mismatches[t]++;
                }
            }
        });

        Assert.Equal([0, 0, 0, 0], mismatches);
    }

    [Fact]
    public void TimedSwitching_RandomGaps_RememberedAnswersEqualTheSearch()
    {
        var rng = new Random(47);
        for (var model = 0; model < 12; model++)
        {
            var timing = RandomTiming(rng);
            for (var i = 0; i < 3000; i++)
            {
                // Log-uniform from a microstep to 10 cm, some asked twice.
                var gap = i % 5 == 4 ? (long)Math.Round(Math.Exp(rng.NextDouble() * Math.Log(1e6))) : (long)Math.Round(Math.Exp((i % 97) / 97.0 * Math.Log(1e6)));
                var fly = timing.ComputeFly(gap);
                Assert.Equal(fly, timing.Fly(gap));
                var plain = (gap - (fly?.GainMicrosteps ?? 0)) / timing.BurnSpeed <= timing.StopGoSeconds(gap);
                Assert.Equal(plain, timing.CrossesGap(gap));
            }
        }
    }

    [Fact]
    public void StrokePlan_RandomStrokes_ReusedAndFreshPlansEqualThePlainComputation()
    {
        var rng = new Random(59);
        var reused = new StrokePlan();
        int nearTheEnd = 0, farFromIt = 0;
        for (var iteration = 0; iteration < 2000; iteration++)
        {
            var timing = RandomTiming(rng);
            var (length, gaps) = RandomStroke(rng, timing);
            var expected = ReferenceStroke.Plan(timing, length, gaps, ref nearTheEnd, ref farFromIt);

            var fresh = timing.Stroke(length, gaps);
            reused.Replan(timing, length, gaps.ToArray());
            foreach (var plan in new[] { fresh, reused })
            {
                Assert.Equal(expected.Bumps, plan.Bumps);
                Assert.Equal(expected.Duration, plan.Duration);
                Assert.Equal(expected.Profile.PeakSpeed, plan.PeakSpeed);
                foreach (var (exit, entry) in gaps)
                {
                    Assert.Equal(expected.TimeAt(exit), plan.TimeAt(exit));
                    Assert.Equal(expected.TimeAt(entry), plan.TimeAt(entry));
                }
            }
        }

        // Both ways of the device-ramp check were taken: with the square root near a stroke's end, without it far from it.
        Assert.True(nearTheEnd > 50 && farFromIt > 1000, $"{nearTheEnd} near the end, {farFromIt} far from it");
    }

    [Fact]
    public void InsertSorted_RandomValues_KeepsTheOrderListSortGives()
    {
        var rng = new Random(61);
        double[] specials = [double.NaN, 0.0, -0.0, double.PositiveInfinity, double.NegativeInfinity, 1.5];
        for (var iteration = 0; iteration < 300; iteration++)
        {
            var list = new List<double>();
            var sorted = new List<double>();
            var ascending = rng.Next(2) == 0;
            for (var i = 0; i < 60; i++)
            {
                // Mostly ascending, as replies come, with some out of order, repeated and special.
                var value = rng.Next(10) switch
                {
                    0 => specials[rng.Next(specials.Length)],
                    1 when list.Count > 0 => list[rng.Next(list.Count)],
                    _ => ascending ? i + (rng.NextDouble() * 3) : rng.NextDouble() * 100,
                };
                MotionTimeline.InsertSorted(list, value);
                sorted.Add(value);
                sorted.Sort();
                Assert.Equal(sorted, list);
            }
        }
    }

    [Fact]
    public void RowRunsFindAndExtent_RowsOfLongWholeWordStretches_MatchABitByBitScan()
    {
        var rng = new Random(67);
        var runs = new int[2];
        for (var iteration = 0; iteration < 300; iteration++)
        {
            var width = (64 * (1 + rng.Next(60))) - (iteration % 3 == 0 ? 0 : rng.Next(63));
            var mask = new BitMask(width, 1);
            var x = 0;
            var black = rng.Next(2) == 0;
            while (x < width)
            {
                // Stretches of 0 to 20 whole words, or a few pixels: both the word-by-word and the vectorised skips.
                var length = rng.Next(3) == 0 ? 1 + rng.Next(5) : (64 * rng.Next(21)) + rng.Next(3);
                for (var i = x; i < Math.Min(width, x + length); i++)
                {
                    mask[i, 0] = black;
                }

                x += Math.Max(1, length);
                black = !black;
            }

            var expected = new List<(int, int)>();
            for (var i = 0; i < width; i++)
            {
                if (mask[i, 0] && (i == 0 || !mask[i - 1, 0]))
                {
                    var runEnd = i;
                    while (runEnd < width && mask[runEnd, 0])
                    {
                        runEnd++;
                    }

                    expected.Add((i, runEnd));
                }
            }

            var count = RowRuns.Find(mask.ReadRow(0), ref runs);
            Assert.Equal(expected, Enumerable.Range(0, count).Select(i => (runs[2 * i], runs[(2 * i) + 1])).ToList());

            // The row's extent, for the timed-room warning: the first run's start and the last one's end.
            var found = RowRuns.Extent(mask.ReadRow(0), out var start, out var end);
            Assert.Equal(expected.Count > 0, found);
            Assert.Equal(expected.Count > 0 ? (expected[0].Item1, expected[^1].Item2) : (0, 0), (start, end));
        }
    }

    [Fact]
    public void ComputeStatistics_RandomMasks_LowerBoundEqualsThePlainSumAndAWarmModelTheCold()
    {
        var rng = new Random(71);
        for (var iteration = 0; iteration < 60; iteration++)
        {
            var width = 20 + rng.Next(400);
            var mask = TestMasks.Random(rng, width, 1 + rng.Next(30));
            var pitch = 3 + (rng.NextDouble() * 400);
            var geometry = TestMasks.Geometry(mask, pitch, ox: 20_000 + rng.Next(100_000), oy: rng.Next(100_000));
            var process = RandomProcess(rng);
            var timing = TimedSwitching.For(process, MachineProfile.Default, TestMasks.Microstep);
            var plan = new RasterPlan(mask, geometry, new PlanOptions { Bidirectional = rng.Next(2) == 0 }, 0, timing);

            var statistics = plan.ComputeStatistics(process);
            Assert.Equal(ReferenceLowerBound(plan, process), statistics.LowerBoundSeconds);

            // The same model asked again (its memos full) and a fresh one (empty) give the same figures, bit for bit.
            var fresh = new RasterPlan(mask, geometry, plan.Options, 0, TimedSwitching.For(process, MachineProfile.Default, TestMasks.Microstep));
            Assert.Equal(statistics, plan.ComputeStatistics(process));
            Assert.Equal(statistics, fresh.ComputeStatistics(process));
            Assert.Equal(plan.Moves(), fresh.Moves());
        }
    }

    private static ProcessSettings RandomProcess(Random rng)
    {
        var burn = 0.2 + (rng.NextDouble() * 3);
        return ProcessSettings.Default with
        {
            BurnSpeedMmPerS = burn,
            TravelSpeedMmPerS = Math.Min(4, burn + (rng.NextDouble() * 4)),
            AccelerationMmPerS2 = 5 + (rng.NextDouble() * 200),
            LaserFrequencyHz = 200 + rng.Next(5000),
        };
    }

    private static TimedSwitching RandomTiming(Random rng)
    {
        var profile = MachineProfile.Default with
        {
            Latency = new LatencyProfile { StageMs = rng.NextDouble() * 3, StageJitterMs = rng.NextDouble(), GateMs = rng.NextDouble() * 3, GateJitterMs = rng.NextDouble() },
        };
        return TimedSwitching.For(RandomProcess(rng), profile, TestMasks.Microstep);
    }

    // A stroke with run-up, runs and gaps of every length; the last gaps often near its end, where the device brakes.
    private static (long Length, List<(long Exit, long Entry)> Gaps) RandomStroke(Random rng, TimedSwitching timing)
    {
        var gaps = new List<(long, long)>();
        var x = timing.RunUpMicrosteps;
        var count = rng.Next(1, 40);
        var shortEnd = rng.Next(2) == 0;
        for (var i = 0; i < count; i++)
        {
            var end = shortEnd && i >= count - 2;
            var run = end ? 1 + rng.Next(1000) : 1 + (long)Math.Exp(rng.NextDouble() * Math.Log(50_000));
            var gap = end ? 1 + rng.Next(3000) : 1 + (long)Math.Exp(rng.NextDouble() * Math.Log(200_000));
            x += run;
            if (i < count - 1)
            {
                gaps.Add((x, x + gap));
                x += gap;
            }
        }

        return (x + timing.RunOutMicrosteps + (shortEnd ? rng.Next(1000) : rng.Next(100_000)), gaps);
    }

    // The lower bound as docs/execution.md defines it, summed move by move with nothing remembered.
    private static double ReferenceLowerBound(RasterPlan plan, ProcessSettings process)
    {
        var microstep = plan.Geometry.MicrostepUm;
        var burn = StageUnits.SpeedMicrostepsPerS(StageUnits.SpeedData(process.BurnSpeedMmPerS, microstep));
        var travel = StageUnits.SpeedMicrostepsPerS(StageUnits.SpeedData(process.TravelSpeedMmPerS, microstep));
        var a = StageUnits.AccelerationMicrostepsPerS2(StageUnits.AccelerationData(process.AccelerationMmPerS2, microstep));
        double StopGo(long d) => d == 0 ? 0 : new TrapezoidProfile(d, travel, a).Duration;
        double Flown(long d)
        {
            if (travel <= burn)
            {
                return d / burn;
            }

            var peak = Math.Min(travel, Math.Sqrt((burn * burn) + (a * d)));
            var ramps = ((peak * peak) - (burn * burn)) / a;
            return (2 * (peak - burn) / a) + ((d - ramps) / peak);
        }

        var seconds = 0.0;
        Move? last = null;
        foreach (var move in plan.Moves().Where(m => m.Kind == MoveKind.Burn))
        {
            if (last is { } l)
            {
                long dx = Math.Abs(move.X0 - l.X1), dy = Math.Abs(move.Y0 - l.Y1);
                seconds += move.Row == l.Row && dy == 0 ? Math.Min(Math.Min(dx / burn, Flown(dx)), StopGo(dx)) : Math.Max(StopGo(dx), StopGo(dy));
            }

            seconds += move.LengthX / burn;
            last = move;
        }

        return seconds;
    }

    /// <summary>A stroke's flown gaps worked out the plain way: each gap searched afresh, the ramp check with its square root.</summary>
    private sealed record ReferenceStroke(TrapezoidProfile Profile, double BurnSpeed, List<StrokePlan.Bump> Bumps, double Gained)
    {
        public double Duration => Profile.Duration - (Gained / BurnSpeed);

        public double TimeAt(long offset)
        {
            var gained = 0.0;
            foreach (var bump in Bumps.TakeWhile(b => offset >= b.Entry))
            {
                gained = bump.GainedUpTo;
            }

            return Profile.TimeAt(offset) - (gained / BurnSpeed);
        }

        public static ReferenceStroke Plan(TimedSwitching timing, long length, List<(long Exit, long Entry)> gaps, ref int nearTheEnd, ref int farFromIt)
        {
            var profile = timing.Stroke(length);
            var burn = timing.BurnSpeed;
            var bumps = new List<StrokePlan.Bump>();
            var gained = 0.0;
            foreach (var (exit, entry) in gaps)
            {
                if (timing.ComputeFly(entry - exit) is not { } fly)
                {
                    continue;
                }

                var a = timing.Acceleration;
                var remaining = length - (exit + (burn * fly.SpeedUpDelaySeconds));
                var root = Math.Sqrt((a * remaining) + (burn * burn / 2));
                _ = root < timing.TravelSpeed ? nearTheEnd++ : farFromIt++;
                var peak = Math.Min(timing.TravelSpeed, root);
                var rise = Math.Min(a * fly.HoldSeconds, timing.TravelSpeed - burn);
                var ramp = rise / a;
                var covered = (burn * fly.HoldSeconds) + (0.5 * rise * ramp) + (rise * (fly.HoldSeconds - ramp));
                if (!(burn + rise <= peak + 1e-9 && covered <= remaining - (peak * peak / (2 * a))))
                {
                    continue;
                }

                var exitTime = profile.TimeAt(exit) - (gained / burn);
                gained += fly.GainMicrosteps;
                var entryTime = profile.TimeAt(entry) - (gained / burn);
                var speedUp = exitTime + fly.SpeedUpDelaySeconds;
                var speedDown = speedUp + fly.HoldSeconds;
                var query = speedDown + fly.QueryDelaySeconds;
                bumps.Add(new StrokePlan.Bump(exit, entry, speedUp, speedDown, query, entry - (burn * (entryTime - query)), fly.MaxErrorMicrosteps, gained));
            }

            return new ReferenceStroke(profile, burn, bumps, gained);
        }
    }
}
