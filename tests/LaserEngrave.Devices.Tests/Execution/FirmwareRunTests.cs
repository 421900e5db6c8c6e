using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Jobs;
using LaserEngrave.Core.Planning;
using LaserEngrave.Devices.Execution;
using LaserEngrave.Devices.Zaber;
using LaserEngrave.Simulator;

namespace LaserEngrave.Devices.Tests.Execution;

/// <summary>The sample jobs on twins of old and new firmware: the host drives each as its firmware allows (docs/zaber-protocol.md, firmware).</summary>
public class FirmwareRunTests
{
    [Theory(Timeout = 120_000)]
    [InlineData("qr-code.bmp", 506)]
    [InlineData("qr-code.bmp", 523)]
    [InlineData("text-banner.png", 506)]
    public async Task RunAsync_SampleImage_BurnsTheMaskOnEitherFirmware(string sample, int firmware)
    {
        var job = TestJobs.FromAsset(sample, 5, new PlanOptions());
        await using var run = SimulatedRun.Create(new SimulatorOptions { FirmwareVersion = firmware });

        var result = await run.Do(() => run.Executor(job).RunAsync(TestContext.Current.CancellationToken));
        var report = run.Analyze(job);

        Assert.True(result.Outcome == RunOutcome.Completed, $"{result.Outcome}: {result.FaultMessage}");
        Assert.Equal(firmware, result.Machine!.X.FirmwareVersion);
        Assert.Equal((0L, 0L, 0, 0), (report.MissingPixels, report.ExtraPixels, report.LaserOnTravelCount, report.RefusedMoves));
    }

    [Theory(Timeout = 120_000)]
    [InlineData(506)]
    [InlineData(523)]
    public async Task RunAsync_Drawing_OnThePathOnEitherFirmware(int firmware)
    {
        var spec = new JobSpec { ImagePath = TestJobs.AssetPath(Path.Combine("drawings", "hexagons.dxf")), Size = SizeSpec.Width(4), Origin = new LaserEngrave.Core.Geometry.OriginMm(5, 5) };
        var job = PreparedDrawing.Prepare(spec, LaserEngrave.Core.Vectors.VectorOptions.Default);
        await using var run = SimulatedRun.Create(new SimulatorOptions { FirmwareVersion = firmware });

        var result = await run.Do(() => new RunExecutor(run.Stage, run.Gate, job, run.Time).RunAsync(TestContext.Current.CancellationToken));
        var report = run.Machine.Recorder.AnalyzePaths(job.Plan.Paths, job.Spec.Process.BurnSpeedMmPerS);

        VectorRunTests.AssertOnPath(result, report, job);
    }

    [Fact(Timeout = 60_000)]
    public async Task SetHomeSpeedAsync_Firmware506_SetsTheTargetSpeedAndHomesAtIt()
    {
        await using var run = SimulatedRun.Create(new SimulatorOptions { FirmwareVersion = 506 });
        var ct = TestContext.Current.CancellationToken;
        var x = run.Stage.X;

        await run.Do(async () =>
        {
            await x.IdentifyAsync(ct);
            await x.SetHomeSpeedAsync(4300, ct);
            await x.HomeAsync(ct);
        });

        Assert.Equal(4300, run.Machine.Stage.X.TargetSpeedData);
        Assert.True(run.Machine.Stage.X.IsHomed);
        Assert.Null(((ZaberBinaryDevice)x).HomeSpeedData);
    }
}
