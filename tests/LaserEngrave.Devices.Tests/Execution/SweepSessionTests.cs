using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Jobs;
using LaserEngrave.Core.Logging;
using LaserEngrave.Core.Planning;
using LaserEngrave.Core.Sweeps;
using LaserEngrave.Devices.Abstractions;
using LaserEngrave.Devices.Execution;
using LaserEngrave.Simulator;
using LaserEngrave.Simulator.Burn;

namespace LaserEngrave.Devices.Tests.Execution;

/// <summary>A parameter sweep in one run on the twin: every cell burned with its own values, the pulses per pixel the arithmetic says, one log.</summary>
public class SweepSessionTests
{
    private static SweepSession Session(SimulatedRun run, SweepPlan plan, RecordingSweepLog log) =>
        new(
            new EngraveMachine(run.Stage, run.Gate, run.Time, "simulator", "simulator") { Simulated = true, Inspector = new BurnInspector(run.Machine) },
            plan,
            new SweepSessionOptions { Log = log, SampleId = "SW-1" });

    private static SweepPlan Plan(string rows, string? columns = null, bool labels = false, ProcessSettings? process = null, SweepPattern pattern = SweepPattern.Square) =>
        SweepPlan.Build(new SweepSpec
        {
            Rows = SweepAxis.Parse(rows, "--rows"),
            Columns = columns is null ? null : SweepAxis.Parse(columns, "--columns"),
            CellMm = 0.3,
            SpacingMm = 0.2,
            PitchUm = 50,
            Origin = new OriginMm(5, 5),
            Labels = labels,
            Pattern = pattern,
            Process = process ?? ProcessSettings.Default,
        });

    [Fact(Timeout = 120_000)]
    public async Task RunAsync_SpeedByFrequency_EachCellGetsPitchTimesFrequencyOverSpeedPulsesAPixel()
    {
        await using var run = SimulatedRun.Create();
        var plan = Plan("speed=0.5,2", "frequency=500,2000", labels: true);
        var log = new RecordingSweepLog();

        var result = await Session(run, plan, log).RunAsync(null, TestContext.Current.CancellationToken);

        var record = Assert.Single(log.Records);
        Assert.True(result.Completed, record.Fault);
        Assert.Equal(4, record.Cells.Count);
        Assert.Equal(RunOutcome.Completed, record.Labels!.Outcome);
        foreach (var cell in record.Cells)
        {
            var run1 = Assert.IsType<RunRecord>(cell.Run);
            var sim = Assert.IsType<RunSimulation>(run1.Simulation);

            // 50 µm pixels: p f / v pulses each, within one pulse (the train's phase at each run's start), and a run's burst
            // stops at the last pulse due before its planned switch-off (up to one fewer than a timed switch-off let through).
            var expected = 50 * cell.Parameters["frequencyHz"] / (cell.Parameters["speedMmPerS"] * 1000);
            Assert.InRange(sim.PulsesPerPixel.Mean, expected - 1.5, expected + 1);
            Assert.Equal((0L, 0L, 0L), (sim.MissingPixels, sim.ExtraPixels, sim.LaserOnTravelCount));
            Assert.Equal(cell.Parameters["speedMmPerS"], run1.Process.BurnSpeedMmPerS);
            Assert.Equal(cell.Parameters["frequencyHz"], run1.Process.LaserFrequencyHz);
        }

        // The place of every cell: 0.5 mm apart, right of and below the labels.
        Assert.Equal(plan.GridXMm + 0.5, record.Cells[1].OriginXMm, 9);
        Assert.Equal(plan.GridYMm + 0.5, record.Cells[2].OriginYMm, 9);
        Assert.Equal(("speed=0.5,2", "frequency=500,2000", "SW-1"), (record.Rows, record.Columns, record.SampleId));

        // The whole sweep on the twin (homing, each job's preflight and travel, the burns) against its estimate.
        var actual = record.Cells.Sum(c => c.Run!.ActualSeconds) + record.Labels.ActualSeconds;
        Assert.True(Math.Abs(actual - plan.EstimatedSeconds) < 0.02 * plan.EstimatedSeconds, $"the sweep took {actual:0.###} s, estimated {plan.EstimatedSeconds:0.###} s");
        Assert.False(run.Machine.Gate.IsFiring);
    }

    [Fact(Timeout = 120_000)]
    public async Task RunAsync_PulsesPerDotSwept_DotArrayCellsGetExactlyTheirCount()
    {
        await using var run = SimulatedRun.Create();
        var plan = Plan("pulses-per-dot=1,4,9", process: ProcessSettings.Default with { Mode = PlanMode.Dots }, pattern: SweepPattern.Dots);
        var log = new RecordingSweepLog();

        await Session(run, plan, log).RunAsync(null, TestContext.Current.CancellationToken);

        var record = Assert.Single(log.Records);
        Assert.Equal(RunOutcome.Completed, record.Outcome);
        foreach (var cell in record.Cells)
        {
            var n = (int)cell.Parameters["pulsesPerDot"];
            var sim = Assert.IsType<RunSimulation>(cell.Run!.Simulation);
            Assert.Equal(new PulseCountRange(n, n, n), sim.PulsesPerPixel);
            Assert.Equal(0L, sim.PulsesWhileMoving);
        }
    }

    [Fact(Timeout = 120_000)]
    public async Task RunAsync_FaultInTheSecondCell_StopsThereLaserOffLaterCellsNotRun()
    {
        // Each cell's preflight and burn take a few dozen stage commands: the fault lands in the second cell.
        await using var run = SimulatedRun.Create(new SimulatorOptions { FaultSpec = "silent:stage:after=110" });
        var plan = Plan("speed=1,2,3");
        var log = new RecordingSweepLog();

        var result = await Session(run, plan, log).RunAsync(null, TestContext.Current.CancellationToken);

        var record = Assert.Single(log.Records);
        Assert.False(result.Completed);
        Assert.Equal(RunOutcome.Failed, record.Outcome);
        Assert.Equal(RunOutcome.Completed, record.Cells[0].Run!.Outcome);
        Assert.NotEqual(RunOutcome.Completed, record.Cells[1].Run!.Outcome);
        Assert.Null(record.Cells[2].Run);
        Assert.StartsWith("cell row 2, column 1", record.Fault, StringComparison.Ordinal);
        Assert.False(run.Machine.Gate.IsFiring);
    }

    private static readonly MachineProfile ThreeAxis = MachineProfile.Default with { Z = new ZAxisProfile { FocusMm = 12.5, MinMm = 5, MaxMm = 20 } };

    private static SweepPlan FocusPlan(string rows, bool labels) =>
        SweepPlan.Build(new SweepSpec
        {
            Rows = SweepAxis.Parse(rows, "--rows"),
            CellMm = 0.2,
            SpacingMm = 0.2,
            PitchUm = 50,
            Pattern = SweepPattern.Lines,
            Origin = new OriginMm(5, 5),
            Labels = labels,
            Profile = ThreeAxis,
        });

    // The stretches in which an axis moved, from its trajectory on the twin.
    private static List<(double From, double To)> Moving(Simulator.Motion.AxisTrajectory axis) =>
        [.. axis.Segments.Where(s => (s.StartVelocity != 0 || s.Acceleration != 0) && s.DurationSeconds > 0).Select(s => (s.StartSeconds, s.EndSeconds))];

    [Fact(Timeout = 120_000)]
    public async Task RunAsync_FocusRows_ZAtEachCellsFocusWhileFiringAndMovedOnlyWithLaserOffStageStill()
    {
        await using var run = SimulatedRun.Create(new SimulatorOptions { TrueFocusOffsetUm = 40, RayleighLengthUm = 100 }, ThreeAxis);
        var plan = FocusPlan("focus=-100,-50,0,50,100", labels: true);
        var log = new RecordingSweepLog();

        var result = await Session(run, plan, log).RunAsync(null, TestContext.Current.CancellationToken);

        var record = Assert.Single(log.Records);
        Assert.True(result.Completed, record.Fault);
        var z = ThreeAxis.Z!;
        foreach (var cell in record.Cells)
        {
            // The planned position, the one the device replied, and where the twin's Z stood whenever the laser fired: all one.
            var expected = z.MicrostepsAt(cell.Parameters["focusUm"]);
            var focus = Assert.IsType<FocusFigures>(cell.Run!.Simulation!.Focus);
            Assert.Equal((expected, expected), (cell.FocusZMicrosteps, cell.ZReachedMicrosteps));
            Assert.Equal((expected, expected, 0), (focus.ZMinMicrosteps, focus.ZMaxMicrosteps, focus.LaserOnWhileZMoving));
            Assert.Equal(StageUnits.MicrostepsToUm(expected, z.MicrostepUm) - ((z.FocusMm * 1000) + 40), focus.DefocusUm, 9);
        }

        // The spot is smallest in the cell nearest the true focus (+40 µm: the +50 µm cell).
        var spots = record.Cells.Select(c => c.Run!.Simulation!.Focus!.SpotDiameterUm!.Value).ToList();
        Assert.Equal(3, spots.IndexOf(spots.Min()));

        // Over the whole sweep, labels included: the laser never fired while Z moved, and Z never moved while X or Y did.
        run.Machine.Recorder.Restart(0);
        Assert.Equal(0, run.Machine.Recorder.FocusWhileFiring()!.Value.PeriodsWhileMoving);
        var zMoves = Moving(run.Machine.Stage.Z!.Trajectory);
        var xyMoves = Moving(run.Machine.Stage.X.Trajectory).Concat(Moving(run.Machine.Stage.Y.Trajectory)).ToList();
        Assert.True(zMoves.Count >= 6, $"Z moved {zMoves.Count} times");
        Assert.DoesNotContain(zMoves, m => xyMoves.Any(o => o.From < m.To && o.To > m.From));

        // Back at the visible focus at the end, laser off.
        Assert.Equal(z.MicrostepsAt(0), run.Machine.Stage.Z.Position);
        Assert.False(run.Machine.Gate.IsFiring);
    }

    [Fact(Timeout = 120_000)]
    public async Task RunAsync_FocusRowsZHomedAtTheFocus_TheTimeBetweenJobsIsTheEstimatedFocusMoves()
    {
        await using var run = SimulatedRun.Create(profile: ThreeAxis);
        var z = ThreeAxis.Z!;
        await run.Do(async () =>
        {
            await run.Stage.Z!.HomeAsync(CancellationToken.None);
            return await run.Stage.Z.MoveAbsoluteAsync(z.MicrostepsAt(0), CancellationToken.None);
        });
        var plan = FocusPlan("focus=-100,0,100,200", labels: true);
        var log = new RecordingSweepLog();
        var start = run.Machine.NowSeconds;

        await Session(run, plan, log).RunAsync(null, TestContext.Current.CancellationToken);

        // Outside the jobs' own times the sweep only moves Z (and, the first time, sets its speed and acceleration).
        var record = Assert.Single(log.Records);
        var between = run.Machine.NowSeconds - start - record.Cells.Sum(c => c.Run!.ActualSeconds) - record.Labels!.ActualSeconds;
        Assert.True(Math.Abs(between - plan.FocusMovesSeconds()) < 0.05 * plan.FocusMovesSeconds(), $"Z moves took {between:0.####} s, estimated {plan.FocusMovesSeconds():0.####} s");
    }

    [Fact(Timeout = 120_000)]
    public async Task RunAsync_ZAxisRefusesItsMove_SweepFailsBeforeTheCellLaserOff()
    {
        await using var run = SimulatedRun.Create(new SimulatorOptions { FaultSpec = "error:stage:device=3:code=20:count=all" }, ThreeAxis);
        var plan = FocusPlan("focus=-50,50", labels: false);
        var log = new RecordingSweepLog();

        var result = await Session(run, plan, log).RunAsync(null, TestContext.Current.CancellationToken);

        var record = Assert.Single(log.Records);
        Assert.False(result.Completed);
        Assert.Equal(RunOutcome.Failed, record.Outcome);
        Assert.StartsWith("cell row 1, column 1 (focus -50 µm): moving the focus to", record.Fault, StringComparison.Ordinal);
        Assert.All(record.Cells, c => Assert.Null(c.Run));
        Assert.False(run.Machine.Gate.IsFiring);
        Assert.Empty(run.Machine.Recorder.LaserOnIntervals(run.Machine.NowSeconds));
    }

    [Fact(Timeout = 120_000)]
    public async Task Abort_WhileZHomes_ZStoppedShortLaserOffNoCellBurned()
    {
        // Z powers up at the far end (25 mm) and homes at 1 mm/s: 5 s into the sweep it is on its way home.
        await using var run = SimulatedRun.Create(profile: ThreeAxis);
        var plan = FocusPlan("focus=-50,50", labels: false);
        var log = new RecordingSweepLog();
        var session = Session(run, plan, log);

        // The abort as a timer on the twin's clock, so it lands at the same virtual instant every time.
        var result = await run.Do(async () =>
        {
            using var timer = run.Time.CreateTimer(_ => session.Abort(), null, TimeSpan.FromSeconds(5), Timeout.InfiniteTimeSpan);
            return await session.RunAsync(null, TestContext.Current.CancellationToken);
        });

        var record = Assert.Single(log.Records);
        Assert.Equal(RunOutcome.Aborted, record.Outcome);
        Assert.StartsWith("aborted by the operator while moving the focus", record.Fault, StringComparison.Ordinal);
        Assert.All(record.Cells, c => Assert.Null(c.Run));
        var z = run.Machine.Stage.Z!;
        Assert.False(z.IsMoving);
        Assert.InRange(z.Position, ThreeAxis.Z!.TravelMicrosteps / 2, ThreeAxis.Z.TravelMicrosteps - 1);
        Assert.False(run.Machine.Gate.IsFiring);
        Assert.False(result.Completed);
    }

    [Fact(Timeout = 60_000)]
    public async Task RunAsync_ProfileWithZStageWithout_RefusedLoggedNothingMoved()
    {
        await using var run = SimulatedRun.Create(profile: ThreeAxis);
        var log = new RecordingSweepLog();
        var machine = new EngraveMachine(new TwoAxes(run.Stage.X, run.Stage.Y), run.Gate, run.Time, "simulator", "simulator") { Simulated = true };

        var result = await new SweepSession(machine, FocusPlan("focus=0", labels: true), new SweepSessionOptions { Log = log }).RunAsync(null, TestContext.Current.CancellationToken);

        var record = Assert.Single(log.Records);
        Assert.Equal(RunOutcome.Refused, record.Outcome);
        Assert.Contains("has a Z axis (device 3) but the stage offers none", record.Fault, StringComparison.Ordinal);
        Assert.Null(record.Labels);
        Assert.False(result.Completed);
        Assert.Equal(ThreeAxis.X.TravelMicrosteps, run.Machine.Stage.X.Position);
    }

    [Fact(Timeout = 60_000)]
    public async Task FocusAxis_ProfileWithZStageWithout_RefusedBeforeAnythingMoves()
    {
        await using var run = SimulatedRun.Create();

        var ex = Assert.Throws<PreflightException>(() => new FocusAxis(new TwoAxes(run.Stage.X, run.Stage.Y), run.Gate, ThreeAxis));

        Assert.Contains("has a Z axis (device 3) but the stage offers none", ex.Message, StringComparison.Ordinal);
    }

    private sealed record TwoAxes(IStageAxis X, IStageAxis Y) : IStage;

    private sealed class RecordingSweepLog : ISweepLogWriter
    {
        public List<SweepRecord> Records { get; } = [];

        public RunLogFiles WriteSweep(SweepRecord record)
        {
            Records.Add(record);
            return new RunLogFiles("sweep.json", "sweep.txt");
        }
    }
}
