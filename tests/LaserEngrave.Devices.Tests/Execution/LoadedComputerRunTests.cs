using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Jobs;
using LaserEngrave.Core.Logging;
using LaserEngrave.Core.Planning;
using LaserEngrave.Devices.Execution;
using LaserEngrave.Simulator;
using LaserEngrave.Simulator.Burn;
using LaserEngrave.Simulator.Timing;
using LaserEngrave.Wire.Serial;

namespace LaserEngrave.Devices.Tests.Execution;

/// <summary>Sample jobs on the front ends' twin, a loaded computer: late wake-ups, stalled writes, late reads, replies in pieces.</summary>
public class LoadedComputerRunTests
{
    [Theory(Timeout = 300_000)]
    [InlineData(1, 1)]
    [InlineData(2, 1)]
    [InlineData(3, 1)]
    [InlineData(1, 4)]
    [InlineData(2, 4)]
    public async Task Session_QrOnTheFrontEndsTwin_CompletesWithNothingOnTheWhite(int seed, double speedMmPerS)
    {
        var job = TestJobs.FromAsset("qr-code.bmp", 5, new PlanOptions(), ProcessSettings.Default with { BurnSpeedMmPerS = speedMmPerS });
        await using var run = SimulatedRun.Create(SimulatorOptions.FrontEnd with { Seed = seed });
        var log = new RecordingLog();
        var session = new EngraveSession(
            new EngraveMachine(run.Stage, run.Gate, run.Time, "simulator", "simulator") { Simulated = true, Inspector = new BurnInspector(run.Machine) },
            job,
            new EngraveSessionOptions { Log = log });

        await session.RunAsync(null, TestContext.Current.CancellationToken);

        var record = Assert.Single(log.Records);
        var simulation = Assert.IsType<RunSimulation>(record.Simulation);
        TestContext.Current.TestOutputHelper?.WriteLine(
            $"QR seed {seed}: {record.Outcome} {record.Fault?.Message}, recoveries {record.Recoveries?.Count ?? 0}, on white {simulation.LaserOnTravelCount}, extra {simulation.ExtraPixels}, edges mean {simulation.Edges?.MeanErrorUm:0.00} max {simulation.Edges?.MaxErrorUm:0.00} µm, {record.EngravingSeconds:0.0} s of {record.EstimatedEngravingSeconds:0.0} estimated");
        Assert.True(record.Outcome == RunOutcome.Completed, $"{record.Outcome}: {record.Fault?.Message}");
        Assert.Equal((0, 0L, 0L), (simulation.LaserOnTravelCount, simulation.ExtraPixels, simulation.MissingPixels));
        Assert.InRange(simulation.Edges!.MaxErrorUm, 0, speedMmPerS > 1 ? 12 : 3);
        Assert.Null(record.LineWarnings);
        Assert.False(run.Machine.Gate.IsFiring);
    }

    [Fact(Timeout = 120_000)]
    public async Task RunAsync_SwitchOnWriteStalled20Ms_ATimingDoubtWithTheLaserSwitchedOffAndNothingOnTheWhite()
    {
        // The computer stalls 20 ms between timing the first switch-on and writing it: the line leaves that much later.
        var job = TestJobs.FromAsset("qr-code.bmp", 5, new PlanOptions());
        await using var run = SimulatedRun.Create(new SimulatorOptions(), (link, time) => new StalledLink(link, time, "BURST", TimeSpan.FromMilliseconds(20)));

        var result = await run.Do(() => run.Executor(job).RunAsync(TestContext.Current.CancellationToken));
        var report = run.Machine.Recorder.Analyze(SimulatedRun.Grid(job), job.Mask, job.Spec.Process.BurnSpeedMmPerS);

        Assert.Equal(RunOutcome.Failed, result.Outcome);
        Assert.Contains("stalled 20.0 ms", result.FaultMessage, StringComparison.Ordinal);
        Assert.Contains("between timing a line to switch the laser on and writing it", result.FaultMessage, StringComparison.Ordinal);
        Assert.True(result.Recoverable);
        Assert.True(result.LaserOffConfirmed);
        Assert.Equal((0, 0L), (report.LaserOnTravelCount, report.ExtraPixels));
        Assert.False(run.Machine.Gate.IsFiring);
    }

    /// <summary>A link whose first write beginning with <paramref name="line"/> stalls <paramref name="stall"/> before its bytes leave.</summary>
    private sealed class StalledLink(ISerialLink inner, TimeProvider time, string line, TimeSpan stall) : ISerialLink
    {
        private bool _stalled;

        public string Name => inner.Name;

        public bool HasUnreadBytes => inner.HasUnreadBytes;

        public ValueTask<int> ReadAsync(Memory<byte> buffer, CancellationToken cancellationToken) => inner.ReadAsync(buffer, cancellationToken);

        public ValueTask<StampedRead> ReadStampedAsync(Memory<byte> buffer, TimeProvider readTime, CancellationToken cancellationToken) => inner.ReadStampedAsync(buffer, readTime, cancellationToken);

        public async ValueTask WriteAsync(ReadOnlyMemory<byte> data, CancellationToken cancellationToken)
        {
            if (!_stalled && System.Text.Encoding.ASCII.GetString(data.Span).StartsWith(line, StringComparison.Ordinal))
            {
                _stalled = true;
                await Task.Delay(stall, time, cancellationToken);
            }

            await inner.WriteAsync(data, cancellationToken);
        }

        public ValueTask DisposeAsync() => inner.DisposeAsync();
    }
}
