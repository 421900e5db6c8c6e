using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Jobs;
using LaserEngrave.Core.Logging;
using LaserEngrave.Core.Planning;
using LaserEngrave.Core.Sweeps;
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

            // 50 µm pixels: p f / v pulses each, within one pulse (the train's phase at each run's start).
            var expected = 50 * cell.Parameters["frequencyHz"] / (cell.Parameters["speedMmPerS"] * 1000);
            Assert.InRange(sim.PulsesPerPixel.Mean, expected - 1, expected + 1);
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
