using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Jobs;
using LaserEngrave.Core.Logging;
using LaserEngrave.Core.Planning;
using LaserEngrave.Devices.Execution;
using LaserEngrave.Simulator;
using LaserEngrave.Simulator.Timing;
using LaserEngrave.Simulator.Burn;

namespace LaserEngrave.Devices.Tests.Execution;

/// <summary>The one use case both front ends call, on the in-process simulator: passes, the burn check, the log, progress and the end state.</summary>
public class EngraveSessionTests
{
    private static PreparedJob Job(int passes = 1, OriginMm? origin = null)
    {
        var job = TestJobs.FromMask(TestJobs.RandomMask(seed: 21, 12, 6), 1, new PlanOptions(), origin);
        return PreparedJob.Prepare(job.Spec with { Passes = passes }, job.Image, job.Mask);
    }

    private static EngraveSession Session(SimulatedRun run, PreparedJob job, RecordingLog log, RunStopPoint? resumeFrom = null, bool inspect = true) =>
        new(
            new EngraveMachine(run.Stage, run.Gate, run.Time, "simulator", "simulator") { Simulated = true, Inspector = inspect ? new BurnInspector(run.Machine) : null },
            job,
            new EngraveSessionOptions { Log = log, SampleId = "S-1", Notes = "session test", ResumeFrom = resumeFrom });

    [Fact(Timeout = 120_000)]
    public async Task RunAsync_TwoPasses_BurnsEveryPixelTwiceAndLogsBothPasses()
    {
        var ct = TestContext.Current.CancellationToken;
        var onePass = new RecordingLog();
        await using (var run = SimulatedRun.Create())
        {
            await Session(run, Job(passes: 1), onePass).RunAsync(null, ct);
        }

        var twoPasses = new RecordingLog();
        await using var twice = SimulatedRun.Create();
        var job = Job(passes: 2);
        var result = await Session(twice, job, twoPasses).RunAsync(null, ct);

        var one = Assert.IsType<RunSimulation>(Assert.Single(onePass.Records).Simulation);
        var record = Assert.Single(twoPasses.Records);
        var two = Assert.IsType<RunSimulation>(record.Simulation);
        Assert.True(record.Outcome == RunOutcome.Completed, $"{record.Outcome}: {record.Fault}");
        Assert.Equal(RunState.Completed, result.State);
        Assert.Equal((2, (int?)2), (record.Passes, record.PassesDone));
        Assert.Equal((job.Statistics.BurnRuns, job.Statistics.Rows), (record.RunsDone, record.RowsDone));
        Assert.Equal((0L, 0L), (two.MissingPixels, two.ExtraPixels));
        Assert.InRange(two.Pulses, 2 * one.Pulses * 0.99, 2 * one.Pulses * 1.01);
        Assert.InRange(two.PulsesPerPixel.Min, 2 * one.PulsesPerPixel.Min - 2, 2 * one.PulsesPerPixel.Min + 2);
        Assert.InRange(two.PulsesPerPixel.Mean, 2 * one.PulsesPerPixel.Mean * 0.99, 2 * one.PulsesPerPixel.Mean * 1.01);
        Assert.InRange(record.LaserOnSeconds, 2 * Assert.Single(onePass.Records).LaserOnSeconds * 0.99, 2 * Assert.Single(onePass.Records).LaserOnSeconds * 1.01);
        Assert.Equal(new RunLogFiles("run.json", "run.txt"), result.Files);
        Assert.Equal(("S-1", "session test", true), (record.SampleId, record.Notes, record.Simulated));
        Assert.False(twice.Machine.Gate.IsFiring);
    }

    [Fact(Timeout = 120_000)]
    public async Task RunAsync_TwoPasses_ProgressGoesThroughBothPassesAndEndsCompletedOnlyAtTheEnd()
    {
        await using var run = SimulatedRun.Create();
        var log = new RecordingLog();
        var reports = new List<EngraveProgress>();
        var session = Session(run, Job(passes: 2), log);

        var result = await session.RunAsync(new SynchronousProgress(reports.Add), TestContext.Current.CancellationToken);

        Assert.Equal([1, 2], reports.Select(r => r.Pass).Distinct());
        Assert.All(reports.Take(reports.Count - 1), r => Assert.False(RunStateMachine.IsEnd(r.State), $"the session reported {r.State} before its end"));
        Assert.Contains(reports, r => r.Pass == 1 && r.Run.State == RunState.Completed && r.State == RunState.Running);
        for (var i = 1; i < reports.Count; i++)
        {
            Assert.True(reports[i].Fraction >= reports[i - 1].Fraction, $"the fraction went back at {i}");
        }

        Assert.Equal(RunState.Completed, reports[^1].State);
        Assert.Equal(1, reports[^1].Fraction, 6);
        Assert.Equal(RunState.Completed, session.State);
        Assert.Equal(RunOutcome.Completed, result.Record.Outcome);
    }

    [Fact(Timeout = 120_000)]
    public async Task Abort_InTheSecondPass_EndsAbortedWithOnePassDoneLoggedAndTheLaserOff()
    {
        await using var run = SimulatedRun.Create();
        var log = new RecordingLog();
        var job = Job(passes: 2);
        EngraveSession? session = null;
        var aborted = 0;
        session = Session(run, job, log);
        var progress = new SynchronousProgress(p =>
        {
            if (p.Pass == 2 && p.MovesDone >= 5 && Interlocked.Exchange(ref aborted, 1) == 0)
            {
                _ = Task.Delay(TimeSpan.FromMilliseconds(100), run.Time).ContinueWith(_ => session.Abort(), run.Loop);
            }
        });

        var result = await session.RunAsync(progress, TestContext.Current.CancellationToken);

        var record = Assert.Single(log.Records);
        Assert.Equal(RunState.Aborted, session.State);
        Assert.Equal(RunState.Aborted, result.State);
        Assert.Equal(RunOutcome.Aborted, record.Outcome);
        Assert.Equal((2, (int?)1), (record.Passes, record.PassesDone));
        Assert.NotNull(record.StoppedAt);
        Assert.Null(result.Error);
        Assert.False(run.Machine.Gate.IsFiring);
    }

    [Fact(Timeout = 60_000)]
    public async Task RunAsync_Cancelled_EndsAbortedAndLogged()
    {
        await using var run = SimulatedRun.Create();
        var log = new RecordingLog();
        using var cancel = CancellationTokenSource.CreateLinkedTokenSource(TestContext.Current.CancellationToken);
        var session = Session(run, Job(), log);

        var result = await session.RunAsync(new SynchronousProgress(p => { if (p.MovesDone >= 3) { cancel.Cancel(); } }), cancel.Token);

        Assert.Equal(RunState.Aborted, result.State);
        Assert.Equal(RunOutcome.Aborted, Assert.Single(log.Records).Outcome);
        Assert.False(run.Machine.Gate.IsFiring);
    }

    [Fact(Timeout = 60_000)]
    public async Task RunAsync_PreflightRefuses_FailedWithTheRefusalLoggedAndReturned()
    {
        await using var run = SimulatedRun.Create();
        var log = new RecordingLog();
        var session = Session(run, Job(origin: new OriginMm(59.5, 10)), log);

        var result = await session.RunAsync(null, TestContext.Current.CancellationToken);

        Assert.IsType<PreflightException>(result.Error);
        Assert.Null(result.Run);
        Assert.Equal(RunState.Failed, session.State);
        var record = Assert.Single(log.Records);
        Assert.Equal(RunOutcome.Refused, record.Outcome);
        Assert.Equal("preflight", record.Fault?.Kind);
        Assert.Equal(0, run.Machine.Recorder.Analyze(SimulatedRun.Grid(session.Job!)).Pulses);
    }

    [Fact(Timeout = 60_000)]
    public async Task RunAsync_LogCannotBeWritten_RunEndsAndTheErrorIsReturned()
    {
        await using var run = SimulatedRun.Create();
        var log = new RecordingLog { Fail = true };

        var result = await Session(run, Job(), log).RunAsync(null, TestContext.Current.CancellationToken);

        Assert.Equal(RunOutcome.Completed, result.Record.Outcome);
        Assert.Null(result.Files);
        Assert.IsType<RunLogException>(result.LogError);
    }

    [Fact(Timeout = 120_000)]
    public async Task RunAsync_ResumingATwoPassJob_RunsOnlyTheRestOfThePassThatStopped()
    {
        var ct = TestContext.Current.CancellationToken;
        await using var run = SimulatedRun.Create();
        var log = new RecordingLog();
        var job = Job(passes: 2);
        using var cancel = CancellationTokenSource.CreateLinkedTokenSource(ct);
        var first = await Session(run, job, log, inspect: false).RunAsync(new SynchronousProgress(p => { if (p.MovesDone >= 10) { cancel.Cancel(); } }), cancel.Token);
        var stop = Assert.IsType<RunStopPoint>(first.Record.StoppedAt);

        // Without the burn check, whose start would leave out what the first run burned.
        var reports = new List<EngraveProgress>();
        var resumed = await Session(run, job, log, stop, inspect: false).RunAsync(new SynchronousProgress(reports.Add), ct);

        Assert.Equal(RunOutcome.Completed, resumed.Record.Outcome);
        Assert.Equal((1, (int?)null, true), (resumed.Record.Passes, resumed.Record.PassesDone, resumed.Record.Resumed));
        Assert.All(reports, r => Assert.Equal(1, r.Pass));
        Assert.True(run.Analyze(job).Burned.ContentEquals(job.Mask));
    }

    [Fact(Timeout = 120_000)]
    public async Task RunAsync_TwiceOnOneSimulator_TheBurnCheckCountsEachSessionAlone()
    {
        var ct = TestContext.Current.CancellationToken;
        await using var run = SimulatedRun.Create();
        var log = new RecordingLog();
        var job = Job();

        await Session(run, job, log).RunAsync(null, ct);
        await Session(run, job, log).RunAsync(null, ct);

        var (first, second) = (log.Records[0].Simulation!, log.Records[1].Simulation!);
        Assert.InRange(second.Pulses, first.Pulses * 0.99, first.Pulses * 1.01);
        Assert.Equal(first.PulsesPerPixel.Max, second.PulsesPerPixel.Max, 1.0);
    }

    [Theory]
    [InlineData(0)]
    [InlineData(101)]
    public async Task Constructor_PassesOutsideOneToHundred_Refused(int passes)
    {
        await using var run = SimulatedRun.Create();
        var job = Job();
        var bad = PreparedJob.Prepare(job.Spec with { Passes = passes }, job.Image, job.Mask);

        Assert.Throws<ArgumentOutOfRangeException>(() => Session(run, bad, new RecordingLog()));
    }

    [Fact(Timeout = 120_000)]
    public async Task RunAsync_FlownGapQueryAnsweredLate_GoesOnFromTheStopPointAndBurnsTheMaskOnce()
    {
        var ct = TestContext.Current.CancellationToken;
        var job = TestJobs.FromAsset("qr-code.bmp", 5, new PlanOptions());
        var clean = new RecordingLog();
        await using (var run = SimulatedRun.Create())
        {
            await Session(run, job, clean).RunAsync(null, ct);
        }

        // The 16th position query of this job is a flown gap's: answered 150 ms late, past the next switch-on's time.
        await using var late = SimulatedRun.Create(new SimulatorOptions { FaultSpec = "delay:stage:device=1:command=60:after=15:ms=150" });
        var log = new RecordingLog();
        var result = await Session(late, job, log).RunAsync(null, ct);

        var record = Assert.Single(log.Records);
        var sim = Assert.IsType<RunSimulation>(record.Simulation);
        var once = Assert.IsType<RunSimulation>(Assert.Single(clean.Records).Simulation);
        Assert.True(record.Outcome == RunOutcome.Completed, $"{record.Outcome}: {record.Fault}");
        Assert.Equal(RunState.Completed, result.State);
        var recovery = Assert.Single(record.Recoveries!);
        Assert.Contains("position query after a flown gap", recovery.Fault, StringComparison.Ordinal);
        Assert.Equal(1, recovery.Pass);
        Assert.Equal((0L, 0L, 0), (sim.MissingPixels, sim.ExtraPixels, sim.LaserOnTravelCount));

        // Nothing burned twice: the doubt came with the laser off, between burn runs.
        Assert.InRange(sim.PulsesPerPixel.Max, 0, once.PulsesPerPixel.Max + 1);
        Assert.InRange(sim.Pulses, once.Pulses * 0.999, once.Pulses * 1.001);
        Assert.False(late.Machine.Gate.IsFiring);
    }

    [Fact(Timeout = 120_000)]
    public async Task RunAsync_EveryQueryLate_GoesOnAtMostMaxRecoveriesTimesThenFailsLaserOff()
    {
        await using var run = SimulatedRun.Create(new SimulatorOptions { FaultSpec = "delay:stage:device=1:command=60:after=15:count=all:ms=150" });
        var log = new RecordingLog();

        var result = await Session(run, TestJobs.FromAsset("qr-code.bmp", 5, new PlanOptions()), log).RunAsync(null, TestContext.Current.CancellationToken);

        var record = Assert.Single(log.Records);
        Assert.Equal(RunOutcome.Failed, record.Outcome);
        Assert.Equal(RunState.Failed, result.State);
        Assert.Equal(EngraveSession.MaxRecoveries, record.Recoveries!.Count);
        Assert.Contains("position query", record.Fault!.Message, StringComparison.Ordinal);
        Assert.Equal((0L, 0), (record.Simulation!.ExtraPixels, record.Simulation.LaserOnTravelCount));
        Assert.False(run.Machine.Gate.IsFiring);
    }

    [Fact(Timeout = 120_000)]
    public async Task RunAsync_AbortAskedAsAPassFailsOnATimingDoubt_EndsAbortedNotFailedOnTheDoubt()
    {
        // A signal that came as a pass ended on a late position query was logged and printed as that doubt ("run failed:
        // ... late"), though the run would have gone on from it and the operator had stopped it.
        await using var run = SimulatedRun.Create(new SimulatorOptions { FaultSpec = "delay:stage:device=1:command=60:after=15:count=all:ms=150" });
        var log = new RecordingLog();
        var session = Session(run, TestJobs.FromAsset("qr-code.bmp", 5, new PlanOptions()), log);
        // The pass's own report of its failure comes before the session decides whether to go on from it.
        var progress = new SynchronousProgress(p =>
        {
            if (p.Run.State == RunState.Failed)
            {
                session.Abort();
            }
        });

        var result = await session.RunAsync(progress, TestContext.Current.CancellationToken);

        var record = Assert.Single(log.Records);
        Assert.Equal(RunOutcome.Aborted, record.Outcome);
        Assert.Equal(RunState.Aborted, result.State);
        Assert.DoesNotContain("position query", record.Fault!.Message, StringComparison.Ordinal);
        Assert.True(record.Fault.LaserOffConfirmed);
        Assert.False(run.Machine.Gate.IsFiring);
    }

    [Fact(Timeout = 120_000)]
    public async Task RunAsync_ManyPassesOnABusyComputer_GoesOnFromMoreDoubtsThanOnePassMayHaveAndCompletes()
    {
        // A late host gives the QR a few doubts a pass; 50 passes need more than MaxRecoveriesInAll in all, which once
        // ended such a job at pass 28 although no pass came near the bound. A gate without scheduled bursts: the host times
        // its switch-ons, so its lateness still gives doubts (a scheduled gate gives hardly any).
        await using var run = SimulatedRun.Create(new SimulatorOptions { HostLateness = HostLateness.Realistic, GateScheduledBursts = false });
        var job = TestJobs.FromAsset("qr-code.bmp", 5, new PlanOptions());
        var log = new RecordingLog();

        await Session(run, PreparedJob.Prepare(job.Spec with { Passes = 50 }, job.Image, job.Mask), log).RunAsync(null, TestContext.Current.CancellationToken);

        var record = Assert.Single(log.Records);
        Assert.True(record.Outcome == RunOutcome.Completed, $"{record.Outcome}: {record.Fault?.Message}");
        Assert.InRange(record.Recoveries!.Count, EngraveSession.MaxRecoveriesInAll + 1, int.MaxValue);
        Assert.All(record.Recoveries.GroupBy(r => r.Pass), pass => Assert.InRange(pass.Count(), 1, EngraveSession.MaxRecoveriesInAll));
        Assert.Equal((0L, 0), (record.Simulation!.ExtraPixels, record.Simulation.LaserOnTravelCount));
        Assert.False(run.Machine.Gate.IsFiring);
    }

    [Fact(Timeout = 120_000)]
    public async Task RunAsync_FaultThatIsNoTimingDoubt_EndsTheRunWithoutGoingOn()
    {
        await using var run = SimulatedRun.Create(new SimulatorOptions { FaultSpec = "error:stage:device=1:command=42:after=3" });
        var log = new RecordingLog();

        await Session(run, TestJobs.FromAsset("qr-code.bmp", 5, new PlanOptions()), log).RunAsync(null, TestContext.Current.CancellationToken);

        var record = Assert.Single(log.Records);
        Assert.Equal(RunOutcome.Failed, record.Outcome);
        Assert.Contains("refused Set Target Speed", record.Fault!.Message, StringComparison.Ordinal);
        Assert.Null(record.Recoveries);
    }

    [Theory(Timeout = 120_000)]
    [InlineData("delay:stage:device=1:command=42:after=3:ms=300")]
    [InlineData("delay:stage:device=1:command=42:after=10:ms=300")]
    [InlineData("drop-reply:stage:device=1:command=42:after=10")]
    public async Task RunAsync_SetTargetSpeedReplyLateOrLost_GoesOnFromTheStopPointAndBurnsTheMaskOnce(string fault)
    {
        // Issue 34: a flown gap's speed reply read past its grace (a host stalled, a reply lost) ended the run; with the
        // laser off confirmed and no burn run cut it is a doubt about time only, and the run goes on as from a late query.
        var ct = TestContext.Current.CancellationToken;
        var job = TestJobs.FromAsset("qr-code.bmp", 5, new PlanOptions());
        var clean = new RecordingLog();
        await using (var run = SimulatedRun.Create())
        {
            await Session(run, job, clean).RunAsync(null, ct);
        }

        await using var late = SimulatedRun.Create(new SimulatorOptions { FaultSpec = fault });
        var log = new RecordingLog();
        var result = await Session(late, job, log).RunAsync(null, ct);

        var record = Assert.Single(log.Records);
        var sim = Assert.IsType<RunSimulation>(record.Simulation);
        var once = Assert.IsType<RunSimulation>(Assert.Single(clean.Records).Simulation);
        Assert.True(record.Outcome == RunOutcome.Completed, $"{record.Outcome}: {record.Fault?.Message}");
        Assert.Equal(RunState.Completed, result.State);
        Assert.Contains(record.Recoveries!, r => r.Fault.StartsWith("the stage did not report Set Target Speed (X", StringComparison.Ordinal));
        Assert.Equal((0L, 0L, 0), (sim.MissingPixels, sim.ExtraPixels, sim.LaserOnTravelCount));
        Assert.InRange(sim.PulsesPerPixel.Max, 0, once.PulsesPerPixel.Max + 1);
        Assert.False(late.Machine.Gate.IsFiring);
    }

    [Fact(Timeout = 120_000)]
    public async Task RunAsync_StageSilentMidRun_GoesOnOnceThenFailsOnTheSilentDeviceLaserOff()
    {
        // A reply that never comes because the device is gone: the doubt is gone on from once, and the recovery's own
        // preflight finds the device silent and ends the run, the cause first.
        await using var run = SimulatedRun.Create(new SimulatorOptions { FaultSpec = "silent:stage:after=60" });
        var log = new RecordingLog();

        var result = await Session(run, TestJobs.FromAsset("qr-code.bmp", 5, new PlanOptions()), log).RunAsync(null, TestContext.Current.CancellationToken);

        var record = Assert.Single(log.Records);
        Assert.Equal(RunOutcome.Failed, record.Outcome);
        Assert.Equal(RunState.Failed, result.State);
        Assert.Single(record.Recoveries!);
        Assert.StartsWith("the X axis (device 1) does not answer as it should", record.Fault!.Message, StringComparison.Ordinal);
        Assert.Contains("while going on after a timing doubt (the stage did not report", record.Fault.Message, StringComparison.Ordinal);
        Assert.True(record.Fault.LaserOffConfirmed);
        Assert.Equal((0L, 0), (record.Simulation!.ExtraPixels, record.Simulation.LaserOnTravelCount));
        Assert.False(run.Machine.Gate.IsFiring);
    }

    [Fact(Timeout = 120_000)]
    public async Task RunAsync_BurnMissesPixelsOfTheMask_EndsFailedNotCompleted()
    {
        // Issue 31, finding 5: a run whose every burn run was sent "completed" (exit 0) with 173 pixels of the mask unburned.
        await using var run = SimulatedRun.Create();
        var log = new RecordingLog();
        var machine = new EngraveMachine(run.Stage, run.Gate, run.Time, "simulator", "simulator") { Simulated = true, Inspector = new MissingPixels(new BurnInspector(run.Machine), 3) };

        var result = await new EngraveSession(machine, Job(), new EngraveSessionOptions { Log = log }).RunAsync(null, TestContext.Current.CancellationToken);

        var record = Assert.Single(log.Records);
        Assert.Equal(RunOutcome.Failed, record.Outcome);
        Assert.Equal(RunState.Failed, result.State);
        Assert.Equal("the burn does not equal the mask: 3 black pixels got no pulse and 0 white pixels got one (the simulator's count), so the image was not engraved whole", record.Fault?.Message);
        Assert.Equal(record.RunsTotal, record.RunsDone);
    }

    [Fact]
    public void BurnMismatch_BurnEqualsTheMaskOrNotMeasured_NullOtherwiseOneLine()
    {
        var record = RunRecord.ForJob(Job(), "hash", DateTimeOffset.UnixEpoch);
        var twin = new RunSimulation(1, 100, null, null, new PulseCountRange(1, 1, 1), 0, 0, 0);

        Assert.Null(EngraveSession.BurnMismatch(record));
        Assert.Null(EngraveSession.BurnMismatch(record with { Simulation = twin }));
        Assert.Equal(
            "the burn does not equal the mask: 0 black pixels got no pulse and 2 white pixels got one (the simulator's count), so the image was not engraved whole",
            EngraveSession.BurnMismatch(record with { Simulation = twin with { ExtraPixels = 2 } }));
    }

    [Fact(Timeout = 120_000)]
    public async Task RunAsync_StageSilentWhileGoingOnAfterADoubt_CauseFirstAndTheLastReportWhereTheRunStopped()
    {
        // Issue 31, finding 8: "this computer was 3.5 ms late ...; going on from it failed: the Y axis (device 2) does not
        // answer": the device came last; and the run bar said row 0 of 33 and drew the cross at 0, 0 while the log said row 8.
        await using var run = SimulatedRun.Create(new SimulatorOptions { FaultSpec = "delay:stage:device=1:command=60:after=15:ms=150,silent:stage:device=2:after=20" });
        var log = new RecordingLog();
        var reports = new List<EngraveProgress>();

        await Session(run, TestJobs.FromAsset("qr-code.bmp", 5, new PlanOptions()), log).RunAsync(new SynchronousProgress(reports.Add), TestContext.Current.CancellationToken);

        var record = Assert.Single(log.Records);
        Assert.Equal(RunOutcome.Failed, record.Outcome);
        Assert.StartsWith("the Y axis (device 2) does not answer", record.Fault!.Message, StringComparison.Ordinal);
        Assert.Contains(", while going on after a timing doubt (the X axis did not answer the position query", record.Fault.Message, StringComparison.Ordinal);
        var stop = Assert.IsType<RunStopPoint>(record.StoppedAt);
        var last = reports[^1];
        Assert.Equal(RunState.Failed, last.State);
        Assert.False(last.Recovering);
        Assert.Equal((record.RowsDone, record.RowsTotal), (last.Run.RowsDone, last.Run.RowsTotal));
        Assert.True(last.Run.RowsDone > 0, "the last report counted no row done");
        Assert.Equal((stop.XMicrosteps, stop.YMicrosteps), (last.Run.XMicrosteps, last.Run.YMicrosteps));
        Assert.False(run.Machine.Gate.IsFiring);
    }

    /// <summary>The twin's burn check, with some black pixels reported unburned.</summary>
    private sealed class MissingPixels(IRunInspector inner, long missing) : IRunInspector
    {
        public void Begin() => inner.Begin();

        public RunSimulation Inspect(PreparedJob job, RunStopPoint? resumedFrom = null) => inner.Inspect(job, resumedFrom) with { MissingPixels = missing };

        public RunSimulation InspectDrawing(PreparedDrawing drawing) => inner.InspectDrawing(drawing);
    }
}
