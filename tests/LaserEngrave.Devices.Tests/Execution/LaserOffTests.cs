using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Jobs;
using LaserEngrave.Core.Logging;
using LaserEngrave.Core.Planning;
using LaserEngrave.Devices.Abstractions;
using LaserEngrave.Devices.Execution;
using LaserEngrave.Simulator;
using Microsoft.Extensions.Time.Testing;
using NSubstitute;

namespace LaserEngrave.Devices.Tests.Execution;

/// <summary>The one laser-off path (<see cref="LaserOff"/>) as runs, test moves and the app use it (issue 31, findings 1, 3 and 4).</summary>
public sealed class LaserOffTests(ITestOutputHelper output)
{
    [Fact(Timeout = 60_000)]
    public async Task SwitchOffAsync_GateFailsWithAnyException_SettlesEveryOneClosesThePortAndSaysAPersonMustCheck()
    {
        var gate = Substitute.For<ILaserGate>();
        gate.EmergencyAsync(Arg.Any<EmergencyCommand>(), Arg.Any<CancellationToken>()).Returns(_ => throw new ObjectDisposedException("laser port"));
        gate.CloseAsync().Returns(_ => throw new InvalidOperationException("already closed"));
        var stops = 0;

        var result = await new LaserOff(gate, new FakeTimeProvider()).SwitchOffAsync(TimeSpan.FromMilliseconds(40), 1000, () =>
        {
            stops++;
            throw new InvalidOperationException("stage gone");
        });

        Assert.Equal(LaserOffPath.None, result.Path);
        Assert.False(result.Confirmed);
        Assert.Contains("a person must check the laser", result.Problem, StringComparison.Ordinal);
        Assert.Equal(1, stops);
        await gate.Received(1).CloseAsync();
        await gate.Received(2).EmergencyAsync(EmergencyCommand.Off, Arg.Any<CancellationToken>());
        await gate.Received(1).EmergencyAsync(EmergencyCommand.FrequencyZero, Arg.Any<CancellationToken>());
        await gate.Received(1).EmergencyAsync(EmergencyCommand.ShortestWatchdog, Arg.Any<CancellationToken>());
    }

    [Fact(Timeout = 60_000)]
    public void ConfirmWindow_DefaultMachine_IsTheTimedSwitchOffsTestNotTheGatesTimeout()
    {
        var window = LaserOff.ConfirmWindow(ProcessSettings.Default, MachineProfile.Default);

        // The switch-off's round trip at 9600 baud, twice the jitter and the 20 ms stall margin: tens of ms, not 500.
        Assert.InRange(window.TotalMilliseconds, 25, 60);
    }

    [Fact(Timeout = 120_000)]
    public async Task RunAsync_StepByStepSwitchOffUnanswered_EmergencyOffWithinItsRoundTripAndNoPingAhead()
    {
        // Issue 31 finding 1: `--strategy paper --fault no-ack:gate:after=8` wrote three PINGs 0.5 s apart after the
        // unanswered OFF, and never OFF again, FREQ 0 or WDOG 50.
        var ct = TestContext.Current.CancellationToken;
        await using var run = SimulatedRun.Create(new SimulatorOptions { FaultSpec = "no-ack:gate:after=8" });
        var job = TestJobs.FromAsset("qr-code.bmp", 5, new PlanOptions { Strategy = PlanStrategy.Paper });

        var result = await run.Do(() => run.Executor(job).RunAsync(ct));

        var gate = run.Written.Where(w => w.Port == "gate").ToList();
        output.WriteLine(string.Join(Environment.NewLine, gate.Select(g => $"{g.Seconds:0.0000} {g.Line}")));
        Assert.Equal(RunOutcome.Failed, result.Outcome);
        Assert.Equal(LaserOffPath.None, result.LaserOffBy);
        var unanswered = gate.FindLastIndex(g => g.Line == "OFF" && gate.IndexOf(g) < gate.Count - 3);
        Assert.Equal(["OFF", "FREQ 0", "WDOG 50"], gate.Skip(unanswered + 1).Select(g => g.Line));
        Assert.All(gate.Skip(unanswered + 1), g => Assert.Equal(gate[unanswered + 1].Seconds, g.Seconds, 6));
        Assert.InRange(gate[unanswered + 1].Seconds - gate[unanswered].Seconds, 0.02, 0.06);
        Assert.False(run.Machine.Gate.IsFiring);
        Assert.Equal(MachineProfileValidator.MinWatchdogMs, run.Machine.Gate.WatchdogMs);
    }

    [Fact(Timeout = 120_000)]
    public async Task RunAsync_StepByStepSwitchOffAnsweredLate_EveryPathAtItsWindowThenTheRunGoesOnAndCompletes()
    {
        // A late answer (a loaded computer on real ports) is in doubt as soon as an unanswered one; it then confirms the
        // laser off, and step by step nothing depends on when: the watchdog is set back and the run goes on.
        var ct = TestContext.Current.CancellationToken;
        var job = TestJobs.FromMask(TestJobs.Mask("..######..", "...#######"), 2, new PlanOptions { Strategy = PlanStrategy.Paper });
        int firstOff;
        await using (var clean = SimulatedRun.Create())
        {
            await clean.Do(() => clean.Executor(job).RunAsync(ct));
            var lines = clean.Written.Where(w => w.Port == "gate").Select(w => w.Line).ToList();
            firstOff = lines.IndexOf("OFF", lines.IndexOf("FREQ 1000"));
        }

        await using var run = SimulatedRun.Create(new SimulatorOptions { FaultSpec = $"delay:gate:after={firstOff}:ms=100" });
        var result = await run.Do(() => run.Executor(job).RunAsync(ct));

        var gate = run.Written.Where(w => w.Port == "gate").ToList();
        output.WriteLine(string.Join(" | ", gate.Select(g => $"{g.Seconds:0.0000} {g.Line}")));
        Assert.Equal(RunOutcome.Completed, result.Outcome);
        Assert.Equal(["OFF", "OFF", "FREQ 0", "WDOG 50", "WDOG 1000"], gate.Skip(firstOff).Take(5).Select(g => g.Line));
        Assert.InRange(gate[firstOff + 1].Seconds - gate[firstOff].Seconds, 0.02, 0.06);
        Assert.Equal(run.Machine.Profile.Gate.WatchdogMs, run.Machine.Gate.WatchdogMs);
        var report = run.Analyze(job);
        Assert.True(report.Burned.ContentEquals(job.Mask), $"{report.ExtraPixels} extra, {report.MissingPixels} missing");
        Assert.Equal(0, report.LaserOnTravelCount);
    }

    [Fact(Timeout = 60_000)]
    public async Task FirePulsesAsync_SwitchOffUnanswered_TestMoveTakesTheRunsEmergencyOffAndFails()
    {
        // The test moves' off was a plain OFF waited for 500 ms; it is the runs' own now.
        var ct = TestContext.Current.CancellationToken;
        await using var run = SimulatedRun.Create(new SimulatorOptions { FaultSpec = "no-ack:gate:after=1" });
        var moves = run.TestMoves();

        var error = await Assert.ThrowsAsync<DeviceException>(() => run.Do(() => moves.FirePulsesAsync(10, 1000, ct)));

        var gate = run.Written.Where(w => w.Port == "gate").Select(g => g.Line).ToList();
        Assert.Equal(["BURST 10 1000", "OFF", "OFF", "FREQ 0", "WDOG 50"], gate);
        Assert.Contains("a person must check the laser", error.Message, StringComparison.Ordinal);
        Assert.False(run.Machine.Gate.IsFiring);
    }

    [Theory(Timeout = 120_000)]
    [InlineData(PlanStrategy.Optimized)]
    [InlineData(PlanStrategy.Paper)]
    public async Task Abort_0To35MsAfterASwitchOn_LoggedOffByOffNotOffAgain(PlanStrategy strategy)
    {
        // Issue 31 finding 3: an abort right after a timed switch-on wrote its OFF behind the BURST; the OFF's reply queued
        // behind the burst's and the fault-free gate was logged as having not answered a switch-off in time (offAgain).
        var ct = TestContext.Current.CancellationToken;
        var job = TestJobs.FromMask(TestJobs.Mask("...######...####", "....############"), 4, new PlanOptions { Strategy = strategy });
        var paths = new List<string>();
        for (var ms = 0; ms < 36; ms++)
        {
            await using var run = SimulatedRun.Create();
            var executor = run.Executor(job);
            var (ons, wasOn) = (0, false);
            var delay = TimeSpan.FromMilliseconds(ms);
            executor.ProgressChanged += (_, p) =>
            {
                if (p.LaserOn && !wasOn && p.State == RunState.Running && ++ons == 2)
                {
                    if (delay == TimeSpan.Zero)
                    {
                        executor.Abort();
                    }
                    else
                    {
                        _ = Task.Delay(delay, run.Time).ContinueWith(_ => executor.Abort(), run.Loop);
                    }
                }

                wasOn = p.LaserOn;
            };

            var result = await run.Do(() => executor.RunAsync(ct));
            Assert.Equal(RunOutcome.Aborted, result.Outcome);
            Assert.DoesNotContain("FREQ 0", run.Written.Where(w => w.Port == "gate").Select(w => w.Line));
            paths.Add($"{ms}:{result.LaserOffBy}");
        }

        output.WriteLine(string.Join(" ", paths));
        Assert.All(paths, p => Assert.EndsWith(":Off", p, StringComparison.Ordinal));
    }

    [Theory(Timeout = 120_000)]
    [InlineData(false)]
    [InlineData(true)]
    public async Task Abort_WhileTheFirstSwitchOnGoesUnanswered_OffWrittenAtOnceNotAfterTheGatesTimeout(bool dots)
    {
        // A step-by-step switch-on (FREQ f) and a dot's burst held the laser lock for the gate's whole 500 ms timeout:
        // the abort's OFF waited behind it.
        var ct = TestContext.Current.CancellationToken;
        await using var run = SimulatedRun.Create(new SimulatorOptions { FaultSpec = "no-ack:gate:after=3" });
        var process = dots ? ProcessSettings.Default with { Mode = PlanMode.Dots, PulsesPerDot = 50 } : null;
        var job = TestJobs.FromMask(TestJobs.Mask("..######..", "...#######"), 2, new PlanOptions { Strategy = PlanStrategy.Paper }, process: process);
        var executor = run.Executor(job);
        var abortedAt = double.NaN;
        var watching = run.Do(async () =>
        {
            while (!run.Written.Any(w => w.Port == "gate" && (w.Line.StartsWith("BURST", StringComparison.Ordinal) || w.Line == "FREQ 1000")))
            {
                await Task.Delay(TimeSpan.FromMilliseconds(1), run.Time, ct);
            }

            await Task.Delay(TimeSpan.FromMilliseconds(10), run.Time, ct);
            abortedAt = run.Machine.NowSeconds;
            executor.Abort();
        });

        var result = await run.Do(() => executor.RunAsync(ct));
        await watching;

        var gate = run.Written.Where(w => w.Port == "gate").ToList();
        output.WriteLine(string.Join(" | ", gate.Select(g => $"{g.Seconds:0.0000} {g.Line}")));
        Assert.Equal(RunOutcome.Aborted, result.Outcome);
        var off = gate.First(g => g.Seconds >= abortedAt && g.Line == "OFF");
        Assert.InRange(off.Seconds - abortedAt, 0, 0.005);
        Assert.False(run.Machine.Gate.IsFiring);
    }

    [Fact(Timeout = 120_000)]
    public async Task FirstSwitchOnCarriedOutNeverAcknowledged_QrAt5Mm_StopPointNamesThePixelAndTheResumeDosesNoOther()
    {
        // Issue 31 finding 4: 46 pulses in pixel (4,4), `cutPixel: null`, and the resume gave it 120 more, unnamed.
        var ct = TestContext.Current.CancellationToken;
        await using var run = SimulatedRun.Create(new SimulatorOptions { FaultSpec = "no-ack:gate:after=4" });
        var job = TestJobs.FromAsset("qr-code.bmp", 5, new PlanOptions());

        var failed = await run.Do(() => run.Executor(job).RunAsync(ct));
        var first = run.Analyze(job);
        var stop = Assert.IsType<RunStopPoint>(failed.StopPoint);
        await run.RecoverAsync();
        var resumed = await run.Do(() => run.Executor(job, new RunOptions { ResumeFrom = stop }).RunAsync(ct));
        var both = run.Analyze(job);

        // 43 since issue 34: the scheduled switch-on's line leaves ahead of its first pulse, so the watchdog, counting from
        // that line, trips that much sooner into the burst.
        Assert.Equal(43, first.Dose.PulsesOnPixel(4, 4));
        Assert.Equal(new PixelIndex(4, 4), stop.OffCutPixel);
        Assert.True(stop.OffByGateWatchdog);
        Assert.Equal(RunOutcome.Completed, resumed.Outcome);
        Assert.True(both.Burned.ContentEquals(job.Mask));
        for (var row = 0; row < job.Mask.Height; row++)
        {
            for (var column = 0; column < job.Mask.Width; column++)
            {
                var before = first.Dose.PulsesOnPixel(column, row);
                if (before >= 5 && both.Dose.PulsesOnPixel(column, row) - before >= 5)
                {
                    Assert.Equal(stop.OffCutPixel, new PixelIndex(column, row));
                }
            }
        }
    }

    [Fact(Timeout = 120_000)]
    public async Task ResumedRunsFirstSwitchOnNeverAcknowledged_StopPointNamesThePixelItCouldDoseTwice()
    {
        // The same at a resumed run's first burn: the gate had answered nothing in that run when it went quiet.
        var ct = TestContext.Current.CancellationToken;
        await using var run = SimulatedRun.Create();
        var job = TestJobs.FromAsset("qr-code.bmp", 5, new PlanOptions());
        var executor = run.Executor(job);
        var ons = 0;
        executor.ProgressChanged += (_, p) =>
        {
            if (p.LaserOn && p.State == RunState.Running && ++ons == 40)
            {
                executor.Abort();
            }
        };
        var aborted = await run.Do(() => executor.RunAsync(ct));
        var stopA = Assert.IsType<RunStopPoint>(aborted.StopPoint);
        var afterA = run.Analyze(job);

        // The resumed run's preflight sends the gate 4 lines (CAPS? the last): the 5th, its first switch-on, is carried out unacknowledged.
        await run.RecoverAsync();
        run.Machine.Faults.Add("no-ack:gate:after=4");
        var failed = await run.Do(() => run.Executor(job, new RunOptions { ResumeFrom = stopA }).RunAsync(ct));
        var stopB = Assert.IsType<RunStopPoint>(failed.StopPoint);
        var afterB = run.Analyze(job);
        await run.RecoverAsync();
        var resumed = await run.Do(() => run.Executor(job, new RunOptions { ResumeFrom = stopB }).RunAsync(ct));
        var all = run.Analyze(job);

        output.WriteLine($"{stopA} / {stopB}");
        Assert.Equal(RunOutcome.Failed, failed.Outcome);
        Assert.Equal(RunOutcome.Completed, resumed.Outcome);
        Assert.True(all.Burned.ContentEquals(job.Mask));
        var named = Assert.IsType<PixelIndex>(stopB.OffCutPixel);
        for (var row = 0; row < job.Mask.Height; row++)
        {
            for (var column = 0; column < job.Mask.Width; column++)
            {
                var inB = afterB.Dose.PulsesOnPixel(column, row) - afterA.Dose.PulsesOnPixel(column, row);
                var inC = all.Dose.PulsesOnPixel(column, row) - afterB.Dose.PulsesOnPixel(column, row);
                if (inB >= 5 && inC >= 5)
                {
                    Assert.Equal(named, new PixelIndex(column, row));
                }
            }
        }
    }
}
