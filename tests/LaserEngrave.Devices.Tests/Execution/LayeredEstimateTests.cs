using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Jobs;
using LaserEngrave.Devices.Execution;

namespace LaserEngrave.Devices.Tests.Execution;

/// <summary>A job of layers homes once: its estimate counts one homing and, for each later layer, the travel from where the one before ended.</summary>
public sealed class LayeredEstimateTests
{
    private static LayeredJob Job() => LayeredJob.Prepare(
        [
            new JobLayer { Name = "hexagons", Source = TestJobs.AssetPath(Path.Combine("drawings", "hexagons.dxf")), Mode = LayerMode.Outline, WidthMm = 3, Origin = new OriginMm(5, 5) },
            new JobLayer { Name = "logo", Source = TestJobs.AssetPath("qr-code.bmp"), Mode = LayerMode.Raster, WidthMm = 1, Origin = new OriginMm(20, 20) },
            new JobLayer { Name = "cut", Source = TestJobs.AssetPath(Path.Combine("drawings", "layers.svg")), DrawingLayer = "cut", Mode = LayerMode.Outline, WidthMm = 4, Origin = new OriginMm(35, 35), Passes = 2 },
        ],
        MachineProfile.Default);

    [Fact]
    public void EstimatedSeconds_LaterLayers_NoHomingEach()
    {
        var job = Job();
        var perLayer = JobPart.RunSeconds(job.Layers);

        Assert.Equal(job.Layers[0].EstimatedSeconds, perLayer[0]);
        Assert.All(Enumerable.Range(1, job.Layers.Count - 1), i => Assert.True(perLayer[i] < job.Layers[i].EstimatedSeconds, $"layer {i + 1}: {perLayer[i]} s, alone {job.Layers[i].EstimatedSeconds} s"));
        Assert.Equal(perLayer.Sum(), job.EstimatedSeconds, 9);
        Assert.Equal(job.EstimatedSeconds, Core.Jobs.EngraveJob.Of(job).EstimatedSeconds, 9);
    }

    [Fact(Timeout = 180_000)]
    public async Task RunAsync_JobOfLayersOnTheTwin_DurationWithinHalfAPercentOfTheEstimate()
    {
        var job = Job();
        var log = new RecordingLog();
        await using var run = SimulatedRun.Create();
        var session = new EngraveSession(new EngraveMachine(run.Stage, run.Gate, run.Time, "simulator", "simulator") { Simulated = true }, job, new EngraveSessionOptions { Log = log });

        var result = await session.RunAsync(new SynchronousProgress(_ => { }), TestContext.Current.CancellationToken);

        Assert.Equal(RunState.Completed, result.State);
        var record = Assert.Single(log.Records);
        var duration = record.ActualSeconds;
        Assert.True(Math.Abs(duration - job.EstimatedSeconds) <= 0.005 * duration, $"twin {duration} s, estimate {job.EstimatedSeconds} s");
        Assert.Equal(job.EstimatedSeconds, record.EstimatedSeconds, 6);
    }
}
