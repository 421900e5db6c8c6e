using LaserEngrave.Core.Jobs;
using LaserEngrave.Core.Logging;
using LaserEngrave.Core.Planning;
using LaserEngrave.Devices.Execution;
using LaserEngrave.Simulator;
using LaserEngrave.Simulator.Burn;

namespace LaserEngrave.Devices.Tests.Execution;

/// <summary>
/// Every gate and stage fault kind at a run's first switch-on, in the middle of a burn and at its last switch-off, timed
/// and step by step (issue 31): no pulse on the white, the laser-off path on the wire (the emergency commands together,
/// nothing ahead of them), and after the resume every pixel dosed in both runs named by the stop point.
/// </summary>
public sealed class LaserOffFaultTableTests(ITestOutputHelper output)
{
    public enum Where
    {
        FirstSwitchOn,
        MidBurst,
        LastSwitchOff,
    }

    private static readonly string[] GateKinds = ["drop-reply", "corrupt", "delay", "error", "silent", "disconnect", "no-ack"];
    private static readonly string[] StageKinds = ["drop-reply", "corrupt", "delay", "error", "silent", "disconnect"];

    public static TheoryData<PlanStrategy, string, string, Where> Faults()
    {
        var data = new TheoryData<PlanStrategy, string, string, Where>();
        foreach (var strategy in new[] { PlanStrategy.Optimized, PlanStrategy.Paper })
        {
            foreach (var where in Enum.GetValues<Where>())
            {
                foreach (var kind in GateKinds)
                {
                    data.Add(strategy, kind, "gate", where);
                }

                foreach (var kind in StageKinds)
                {
                    data.Add(strategy, kind, "stage", where);
                }
            }
        }

        return data;
    }

    [Theory(Timeout = 120_000)]
    [MemberData(nameof(Faults))]
    public async Task Run_FaultAtEachPlace_NoPulseOnWhiteLaserOffOnTheWireAndEveryPixelDosedTwiceNamed(PlanStrategy strategy, string kind, string target, Where where)
    {
        var ct = TestContext.Current.CancellationToken;
        var job = Job(strategy);
        var after = await AfterAsync(job, target, where, ct);
        var fault = kind == "delay" ? $"delay:{target}:after={after}:ms=300" : $"{kind}:{target}:after={after}";
        await using var run = SimulatedRun.Create(new SimulatorOptions { FaultSpec = fault });

        var first = await run.Do(() => run.Executor(job).RunAsync(ct));

        // A gate that could not be told: its watchdog switches the laser off, before anyone resumes.
        await run.Do(() => Task.Delay(TimeSpan.FromMilliseconds(run.Machine.Profile.Gate.WatchdogMs * 2), run.Time, ct));
        var burned = run.Analyze(job);
        var gate = run.Written.Where(w => w.Port == "gate").ToList();
        output.WriteLine($"{strategy} {fault}: {first.Outcome}, off by {first.LaserOffBy}, {first.FaultMessage}; stop {first.StopPoint}");
        output.WriteLine(string.Join(" | ", gate.TakeLast(8).Select(g => $"{g.Seconds:0.0000} {g.Line}")));

        Assert.False(run.Machine.Gate.IsFiring);
        Assert.Equal(0, burned.ExtraPixels);
        Assert.Equal(0, burned.LaserOnTravelCount);
        AssertOffOnTheWire(first, gate, linkLost: kind == "disconnect" && target == "gate");
        if (first.Outcome != RunOutcome.Failed)
        {
            return;
        }

        var stop = Assert.IsType<RunStopPoint>(first.StopPoint);
        var tripped = run.Machine.Gate.WatchdogTrips > 0;
        await run.RecoverAsync();
        var resumed = await run.Do(() => run.Executor(job, new RunOptions { ResumeFrom = stop }).RunAsync(ct));
        var both = run.Analyze(job);
        var twice = DosedInBoth(job, burned, both);
        output.WriteLine($"resumed: {resumed.Outcome}; {both.ExtraPixels} extra, {both.MissingPixels} missing; dosed in both: {string.Join(" ", twice)}");

        Assert.Equal(RunOutcome.Completed, resumed.Outcome);
        Assert.True(both.Burned.ContentEquals(job.Mask), $"{both.ExtraPixels} extra, {both.MissingPixels} missing");
        Assert.Equal(0, both.LaserOnTravelCount);
        if (twice.Count == 0)
        {
            return;
        }

        // The pixel the log names: where the laser went off, or, when the gate's watchdog did not trip, at its first OFF;
        // a run burned again from its start (its switch-on never acknowledged) may dose the pixels before it too.
        var named = stop.OffByGateWatchdog && !tripped && stop.OffCutPixel is { } off ? off : stop.CutPixel;
        var cut = Assert.IsType<PixelIndex>(named);
        var fromStart = stop.OffByGateWatchdog && !tripped ? stop.OffResumeXMicrosteps is null : stop.ResumeXMicrosteps is null;
        if (!fromStart)
        {
            Assert.Equal([cut], twice);
        }
        else
        {
            // Burned again from its start: the pixels from the run's first to the one named (where it went off at the latest).
            var run0 = job.Plan.Moves().ElementAt(checked((int)stop.MoveIndex));
            var firstColumn = job.Plan.ColumnAt(run0, run0.X0 + Math.Sign(run0.X1 - run0.X0));
            Assert.All(twice, p =>
            {
                Assert.Equal(cut.Row, p.Row);
                Assert.InRange(p.Column, Math.Min(firstColumn, cut.Column), Math.Max(firstColumn, cut.Column));
            });
        }
    }

    // Off on the wire: once a switch-off is in doubt, OFF, FREQ 0 and WDOG 50 leave together with no PING before them,
    // and nothing follows a port closed; a switch-off acknowledged leaves no emergency command.
    private static void AssertOffOnTheWire(RunResult result, List<(double Seconds, string Port, string Line)> gate, bool linkLost)
    {
        var lines = gate.Select(g => g.Line).ToList();
        var zero = lines.IndexOf("FREQ 0");
        if (linkLost)
        {
            // Nothing can be written to a link that is gone: its port is closed at once and the gate's watchdog is left.
            Assert.Equal(LaserOffPath.None, result.LaserOffBy);
            Assert.Equal(-1, zero);
            return;
        }

        if (result.LaserOffBy is LaserOffPath.OffAgain or LaserOffPath.FrequencyZero or LaserOffPath.None
            || (result.Outcome == RunOutcome.Completed && zero > 0))
        {
            Assert.True(zero > 0, string.Join(" | ", lines));
            Assert.Equal(["OFF", "FREQ 0", "WDOG 50"], lines.Skip(zero - 1).Take(3));
            Assert.Equal(gate[zero - 1].Seconds, gate[zero + 1].Seconds, 6);
            var doubted = lines.LastIndexOf("OFF", zero - 2);
            Assert.True(doubted >= 0);
            Assert.DoesNotContain("PING", lines.Skip(doubted).Take(zero - doubted));
            Assert.InRange(gate[zero - 1].Seconds - gate[doubted].Seconds, 0, 0.1);
            if (result.LaserOffBy == LaserOffPath.None)
            {
                Assert.Equal(zero + 1, lines.Count - 1);
            }

            if (result.Outcome == RunOutcome.Completed)
            {
                // A step-by-step switch-off answered late: every path went out at its window, then the watchdog set back.
                Assert.Contains("WDOG 1000", lines.Skip(zero + 2));
            }
        }
        else
        {
            Assert.True(result.LaserOffConfirmed);
            Assert.Equal(-1, zero);
            Assert.Equal("OFF", lines[^1]);
        }
    }

    private static PreparedJob Job(PlanStrategy strategy) =>
        TestJobs.FromMask(TestJobs.Mask("..######..####..", "....############", "###...#####....."), 4, new PlanOptions { Strategy = strategy });

    /// <summary>How many commands of <paramref name="target"/> a fault-free run sends before the place asked for.</summary>
    private static async Task<int> AfterAsync(PreparedJob job, string target, Where where, CancellationToken ct)
    {
        await using var run = SimulatedRun.Create();
        var result = await run.Do(() => run.Executor(job).RunAsync(ct));
        Assert.Equal(RunOutcome.Completed, result.Outcome);
        var gate = run.Written.Where(w => w.Port == "gate").ToList();
        var ons = gate.Select((g, i) => (g, i)).Where(x => x.g.Line.StartsWith("BURST", StringComparison.Ordinal) || (x.g.Line.StartsWith("FREQ ", StringComparison.Ordinal) && x.g.Line != "FREQ 0")).Select(x => x.i).ToList();
        var lastOn = ons[^1];
        var lastOff = gate.FindIndex(lastOn, g => g.Line == "OFF");
        var line = where switch
        {
            Where.FirstSwitchOn => ons[0],
            Where.MidBurst => ons[ons.Count / 2] + 1,
            _ => lastOff,
        };
        if (target == "gate")
        {
            return line;
        }

        // The stage's first command written at or after that gate line, where the stage is working as the laser switches;
        // at the last switch-off the last one before it (a timed run has sent its last stroke's moves by then).
        var at = gate[line].Seconds;
        var before = run.Written.Where(w => w.Port == "stage").Count(w => w.Seconds < at);
        return where == Where.LastSwitchOff ? before - 1 : before;
    }

    // A pixel dosed in both runs: a part of its dose in each (a few pulses over its edge from the stage's jitter aside).
    private static List<PixelIndex> DosedInBoth(PreparedJob job, BurnReport first, BurnReport both)
    {
        const int Some = 5;
        var pixels = new List<PixelIndex>();
        for (var row = 0; row < job.Mask.Height; row++)
        {
            for (var column = 0; column < job.Mask.Width; column++)
            {
                var before = first.Dose.PulsesOnPixel(column, row);
                if (before >= Some && both.Dose.PulsesOnPixel(column, row) - before >= Some)
                {
                    pixels.Add(new PixelIndex(column, row));
                }
            }
        }

        return pixels;
    }
}
