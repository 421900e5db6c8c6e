using LaserEngrave.Core.Jobs;
using LaserEngrave.Core.Logging;
using LaserEngrave.Core.Planning;
using LaserEngrave.Devices.Execution;
using LaserEngrave.Simulator;
using LaserEngrave.Simulator.Burn;

namespace LaserEngrave.Devices.Tests.Execution;

/// <summary>Dot mode on the twin: the stage stops at each dot, the gate fires exactly N pulses, nothing fires while moving, and the estimate holds.</summary>
public class DotModeRunTests
{
    private static ProcessSettings Dots(int pulses, long pitchMicrosteps = 0, double settleMs = 0) =>
        ProcessSettings.Default with { Mode = PlanMode.Dots, PulsesPerDot = pulses, DotPitchMicrosteps = pitchMicrosteps, DotSettleMs = settleMs };

    private static EngraveSession Session(SimulatedRun run, PreparedJob job, RecordingLog log) =>
        new(
            new EngraveMachine(run.Stage, run.Gate, run.Time, "simulator", "simulator") { Simulated = true, Inspector = new BurnInspector(run.Machine) },
            job,
            new EngraveSessionOptions { Log = log });

    [Theory(Timeout = 120_000)]
    [InlineData(1, 0)]
    [InlineData(5, 0)]
    [InlineData(7, 3)]
    public async Task Session_DotAtEveryPixel_EachBlackPixelGetsExactlyNPulsesAndNoneWhileMoving(int pulses, double settleMs)
    {
        await using var run = SimulatedRun.Create();
        var job = TestJobs.FromMask(TestJobs.RandomMask(seed: 31, 12, 6), 1, new PlanOptions(), process: Dots(pulses, settleMs: settleMs));
        var log = new RecordingLog();

        var result = await Session(run, job, log).RunAsync(null, TestContext.Current.CancellationToken);

        var record = Assert.Single(log.Records);
        var sim = Assert.IsType<RunSimulation>(record.Simulation);
        var black = job.Mask.CountSet();
        Assert.True(record.Outcome == RunOutcome.Completed, $"{record.Outcome}: {record.Fault}");
        Assert.Equal(PlanMode.Dots, record.Process.Mode);
        Assert.Equal(pulses, record.Process.PulsesPerDot);
        Assert.Equal(new PulseCountRange(pulses, pulses, pulses), sim.PulsesPerPixel);
        Assert.Equal(black * pulses, sim.Pulses);
        Assert.Equal(0L, sim.PulsesWhileMoving);
        Assert.Equal((0L, 0L, 0L), (sim.MissingPixels, sim.ExtraPixels, sim.LaserOnTravelCount));
        Assert.Equal((black, black), (record.RunsDone, record.RunsTotal));
        Assert.Equal(black * pulses / 1000.0, record.LaserOnSeconds, 9);
        Assert.False(run.Machine.Gate.IsFiring);
        Assert.Equal(RunState.Completed, result.State);
    }

    [Fact(Timeout = 120_000)]
    public async Task Session_DotPitchAQuarterPixel_FloorOfTheRunOverThePitchDotsAllStanding()
    {
        await using var run = SimulatedRun.Create();

        // 10 px over 0.5 mm: 50 µm pixels of 503.94 microsteps; a dot every 125 microsteps (12.4 µm): 4.03 dots a pixel, so
        // floor(4.03 n) centred on a run of n pixels: 4 on each single pixel, 8 on the pair, 40 on the row of 10.
        var mask = TestJobs.Mask("##########", "....##....", "#.#.#.#.#.");
        var job = TestJobs.FromMask(mask, 0.5, new PlanOptions(), process: Dots(3, 125));
        var log = new RecordingLog();

        await Session(run, job, log).RunAsync(null, TestContext.Current.CancellationToken);

        var sim = Assert.IsType<RunSimulation>(Assert.Single(log.Records).Simulation);
        var dots = Assert.IsType<DotPlan>(job.Dots);
        Assert.Equal(40 + 8 + (5 * 4), dots.Estimate.Dots);
        Assert.Equal(dots.Estimate.Dots * 3, sim.Pulses);
        Assert.Equal(0L, sim.PulsesWhileMoving);
        Assert.Equal((0L, 0L, 0L), (sim.MissingPixels, sim.ExtraPixels, sim.LaserOnTravelCount));

        // 68 dots of 3 pulses on 17 black pixels: 12 a pixel on average, as the arithmetic says (3 x 50 / 12.4 = 12.09).
        Assert.Equal(12, sim.PulsesPerPixel.Mean, 9);
        Assert.InRange(sim.PulsesPerPixel.Min, 9, 12);
        Assert.InRange(sim.PulsesPerPixel.Max, 12, 15);
        Assert.Equal(job.Pulses.PulsesPerPixel!.Value, sim.PulsesPerPixel.Mean, 0.1);
    }

    // A paper plan moves between dots at the burn speed: its estimate was 20 % short when it assumed the travel speed.
    [Theory(Timeout = 120_000)]
    [InlineData(PlanStrategy.Optimized)]
    [InlineData(PlanStrategy.Paper)]
    public async Task Session_QrSampleTenPulsesADot_EstimateWithinTwoPercentOfTheTwin(PlanStrategy strategy)
    {
        await using var run = SimulatedRun.Create();
        var job = TestJobs.FromAsset("qr-code.bmp", 5, new PlanOptions { Strategy = strategy }, Dots(10));
        var log = new RecordingLog();

        await Session(run, job, log).RunAsync(null, TestContext.Current.CancellationToken);

        var record = Assert.Single(log.Records);
        var sim = Assert.IsType<RunSimulation>(record.Simulation);
        Assert.Equal(RunOutcome.Completed, record.Outcome);
        Assert.Equal(new PulseCountRange(10, 10, 10), sim.PulsesPerPixel);
        Assert.Equal(0L, sim.PulsesWhileMoving);
        var engraving = job.Statistics.EngravingSeconds;
        Assert.True(Math.Abs(record.EngravingSeconds - engraving) < 0.02 * engraving, $"engraving {record.EngravingSeconds:0.###} s against the estimate {engraving:0.###} s");
        if (strategy == PlanStrategy.Optimized)
        {
            // The homing and the move to the first dot are modelled at the travel speed only (a paper plan's, at the
            // burn speed, is not: docs/process.md).
            Assert.True(
                Math.Abs(record.ActualSeconds - record.EstimatedSeconds) < 0.02 * record.EstimatedSeconds,
                $"the whole run {record.ActualSeconds:0.###} s against the estimate {record.EstimatedSeconds:0.###} s");
        }
    }

    [Fact(Timeout = 120_000)]
    public async Task RunAsync_AbortMidDots_LaserOffAndNoPulseWhileMoving()
    {
        var ct = TestContext.Current.CancellationToken;
        await using var run = SimulatedRun.Create();
        var job = TestJobs.FromMask(TestJobs.RandomMask(seed: 5, 12, 6), 1, new PlanOptions(), process: Dots(20));
        var executor = run.Executor(job);
        executor.MoveCompleted += (_, e) =>
        {
            if (e.MoveIndex == 9)
            {
                executor.Abort();
            }
        };

        var result = await run.Do(() => executor.RunAsync(ct));
        var report = run.Machine.Recorder.Analyze(SimulatedRun.Grid(job), job.Mask);

        Assert.Equal(RunOutcome.Aborted, result.Outcome);
        Assert.False(run.Machine.Gate.IsFiring);
        Assert.Equal(0, report.PulsesWhileMoving);
        Assert.Equal(10 * 20, report.Pulses);
        Assert.Equal(10, Assert.IsType<RunStopPoint>(result.StopPoint).MoveIndex);
    }

    [Fact(Timeout = 120_000)]
    public async Task Pause_MidDots_StandsWithTheLaserOffAndResumeFiresEveryDotOnce()
    {
        await using var run = SimulatedRun.Create();
        var job = TestJobs.FromMask(TestJobs.RandomMask(seed: 9, 12, 6), 1, new PlanOptions(), process: Dots(6));
        var executor = run.Executor(job);
        var states = new List<RunState>();
        bool? firingWhilePaused = null;
        executor.MoveCompleted += (_, e) =>
        {
            if (e.MoveIndex == 7)
            {
                executor.Pause();
            }
        };
        executor.StateChanged += (_, e) =>
        {
            states.Add(e.State);
            if (e.State == RunState.Paused)
            {
                firingWhilePaused = run.Machine.Gate.IsFiring;
                _ = Task.Delay(TimeSpan.FromSeconds(2), run.Time).ContinueWith(_ => executor.Resume(), run.Loop);
            }
        };

        var result = await run.Do(() => executor.RunAsync(TestContext.Current.CancellationToken));
        var report = run.Analyze(job);

        Assert.True(result.Outcome == RunOutcome.Completed, $"{result.Outcome}: {result.FaultMessage}");
        Assert.Equal([RunState.Preflight, RunState.Running, RunState.Pausing, RunState.Paused, RunState.Running, RunState.Completed], states);
        Assert.False(firingWhilePaused);
        Assert.Equal((6, 6), (report.PulsesPerPixel.Min, report.PulsesPerPixel.Max));
        Assert.Equal(0, report.PulsesWhileMoving);
        Assert.True(result.Duration - result.EngravingDuration >= TimeSpan.FromSeconds(2), "the pause is counted as engraving time");
    }

    [Theory(Timeout = 120_000)]
    [InlineData("no-ack:gate:after=20")]
    [InlineData("silent:stage:after=60")]
    public async Task RunAsync_FaultMidDots_FailsWithLaserOffAndResumeFinishesEveryDot(string fault)
    {
        var ct = TestContext.Current.CancellationToken;
        await using var run = SimulatedRun.Create(new SimulatorOptions { FaultSpec = fault });
        var job = TestJobs.FromMask(TestJobs.RandomMask(seed: 7, 12, 6), 1, new PlanOptions(), process: Dots(4));

        var failed = await run.Do(() => run.Executor(job).RunAsync(ct));
        if (!failed.LaserOffConfirmed)
        {
            await run.Do(() => Task.Delay(TimeSpan.FromMilliseconds(run.Machine.Profile.Gate.WatchdogMs * 2), run.Time, ct));
        }

        Assert.Equal(RunOutcome.Failed, failed.Outcome);
        Assert.False(run.Machine.Gate.IsFiring);
        var stop = Assert.IsType<RunStopPoint>(failed.StopPoint);
        Assert.InRange(stop.MoveIndex, 1, job.Statistics.Moves - 1);

        await run.RecoverAsync();
        var resumed = await run.Do(() => run.Executor(job, new RunOptions { ResumeFrom = stop }).RunAsync(ct));
        var report = run.Analyze(job);

        Assert.Equal(RunOutcome.Completed, resumed.Outcome);
        Assert.Equal(job.Statistics.BurnRuns, resumed.RunsDone);
        Assert.True(report.Burned.ContentEquals(job.Mask), $"{fault}: {report.ExtraPixels} extra, {report.MissingPixels} missing");
        Assert.Equal(0, report.PulsesWhileMoving);

        // A dot whose burst the fault cut is fired again whole: at most one dot gets more than its 4 pulses.
        Assert.Equal(4, report.PulsesPerPixel.Min);
        Assert.InRange(report.PulsesPerPixel.Max, 4, 8);
    }
}
