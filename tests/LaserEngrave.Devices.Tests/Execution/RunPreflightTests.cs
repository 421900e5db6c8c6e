using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Jobs;
using LaserEngrave.Core.Planning;
using LaserEngrave.Core.Vectors;
using LaserEngrave.Devices.Abstractions;
using LaserEngrave.Devices.Execution;
using NSubstitute;

namespace LaserEngrave.Devices.Tests.Execution;

/// <summary>The preflight alone (<see cref="RunPreflight"/>), against fake axes and a fake gate: what the run starts from.</summary>
public class RunPreflightTests
{
    private const int TravelSpeedData = 2000;
    private const int AccelerationData = 30;

    private static readonly AxisIdentity Homed = new(1, 4212, 502, 0x80, 604_724);
    private static readonly AxisIdentity NotHomed = Homed with { DeviceMode = 0 };

    [Fact(Timeout = 60_000)]
    public async Task RunAsync_OneAxisNotHomed_HomesItAloneAtTheProcessSettingsAndReportsWhereBothAre()
    {
        var (stage, gate) = Fakes(NotHomed, Homed);
        stage.X.GetPositionAsync(Arg.Any<CancellationToken>()).Returns(0L);
        stage.Y.GetPositionAsync(Arg.Any<CancellationToken>()).Returns(1234L);
        var job = TestJobs.FromMask(TestJobs.RandomMask(1, 8, 8), 1, new PlanOptions { Strategy = PlanStrategy.Paper });

        var found = await Preflight(stage, gate, job, RunOptions.Default).RunAsync(TestContext.Current.CancellationToken);

        Assert.True(found.Homed);
        Assert.Equal((0L, 1234L), (found.X, found.Y));
        await stage.X.Received(1).SetAccelerationAsync(AccelerationData, Arg.Any<CancellationToken>());
        await stage.X.Received(1).SetHomeSpeedAsync(TravelSpeedData, Arg.Any<CancellationToken>());
        await stage.X.Received(1).HomeAsync(Arg.Any<CancellationToken>());
        await stage.Y.DidNotReceiveWithAnyArgs().HomeAsync(Arg.Any<CancellationToken>());
        await stage.Y.DidNotReceiveWithAnyArgs().SetHomeSpeedAsync(Arg.Any<int>(), Arg.Any<CancellationToken>());
        await gate.Received(1).OffAsync(Arg.Any<CancellationToken>());
        await gate.Received(1).SetWatchdogAsync(job.Spec.Profile.Gate.WatchdogMs, Arg.Any<CancellationToken>());
        Assert.Equal("PICGATE 1.0", found.Identity.Gate);
    }

    [Fact(Timeout = 60_000)]
    public async Task RunAsync_ResumeCountingOnAWatchdogThatDidNotTrip_TakesTheCutAtTheFirstOff()
    {
        var (stage, gate) = Fakes(Homed, Homed);
        gate.GetStateAsync(Arg.Any<CancellationToken>()).Returns(new LaserGateState(0, false, 1000, WatchdogTripped: false));
        var job = TestJobs.FromMask(TestJobs.RandomMask(1, 8, 8), 1, new PlanOptions());
        var stop = new RunStopPoint(2, 10) { ResumeXMicrosteps = 500, OffByGateWatchdog = true, OffResumeXMicrosteps = 480 };

        var found = await Preflight(stage, gate, job, new RunOptions { ResumeFrom = stop }).RunAsync(TestContext.Current.CancellationToken);

        Assert.Equal(480, found.ResumeX);
        Assert.False(found.GateVouchesForCut);
        Assert.False(found.Homed);
    }

    [Fact(Timeout = 60_000)]
    public async Task RunAsync_WiderSpreadAskedForATimedRaster_TimesTheRunWithIt()
    {
        var (stage, gate) = Fakes(Homed, Homed);
        var job = TestJobs.FromMask(TestJobs.RandomMask(1, 8, 8), 1, new PlanOptions());
        var planned = job.Plan.Timing!;

        var found = await Preflight(stage, gate, job, new RunOptions { LatencyScale = 2 }).RunAsync(TestContext.Current.CancellationToken);

        Assert.Equal(2, found.LatencyScale);
        Assert.Equal(2 * planned.StageJitterSeconds, found.Timing!.StageJitterSeconds, 12);
        Assert.Equal(2 * planned.GateJitterSeconds, found.Timing.GateJitterSeconds, 12);
    }

    [Fact(Timeout = 60_000)]
    public async Task RunAsync_WiderSpreadAskedForAStepByStepPlan_KeepsTheProfilesLatencies()
    {
        var (stage, gate) = Fakes(Homed, Homed);
        var job = TestJobs.FromMask(TestJobs.RandomMask(1, 8, 8), 1, new PlanOptions { Strategy = PlanStrategy.Paper });

        var found = await Preflight(stage, gate, job, new RunOptions { LatencyScale = 2 }).RunAsync(TestContext.Current.CancellationToken);

        Assert.Equal(1, found.LatencyScale);
        Assert.Null(found.Timing);
    }

    [Fact(Timeout = 60_000)]
    public async Task RunAsync_AxisShorterThanTheJob_RefusesBeforeHoming()
    {
        var (stage, gate) = Fakes(NotHomed with { MaximumPosition = 1000 }, NotHomed);
        var job = TestJobs.FromMask(TestJobs.RandomMask(1, 8, 8), 1, new PlanOptions());

        var ex = await Assert.ThrowsAsync<PreflightException>(() => Preflight(stage, gate, job, RunOptions.Default).RunAsync(TestContext.Current.CancellationToken));

        Assert.StartsWith("the job reaches X = ", ex.Message, StringComparison.Ordinal);
        await stage.X.DidNotReceiveWithAnyArgs().HomeAsync(Arg.Any<CancellationToken>());
        await stage.Y.DidNotReceiveWithAnyArgs().HomeAsync(Arg.Any<CancellationToken>());
    }

    [Fact(Timeout = 60_000)]
    public async Task RunAsync_DrawingReachesPastAnAxisMaximum_RefusesBeforeHoming()
    {
        var (stage, gate) = Fakes(NotHomed with { MaximumPosition = 1000 }, NotHomed);
        var drawing = PreparedDrawing.Prepare(
            new JobSpec { ImagePath = TestJobs.AssetPath(Path.Combine("drawings", "hexagons.dxf")), Size = SizeSpec.Width(4), Origin = new OriginMm(5, 5) },
            VectorOptions.Default);
        var part = EngraveJob.Of(drawing).Parts[0];
        var preflight = new RunPreflight(stage, gate, part, part.Program(), drawing.Spec.Process, drawing.Spec.Profile, drawing.Schedule.Timing, TravelSpeedData, AccelerationData, RunOptions.Default);

        var ex = await Assert.ThrowsAsync<PreflightException>(() => preflight.RunAsync(TestContext.Current.CancellationToken));

        Assert.StartsWith("the job reaches X = ", ex.Message, StringComparison.Ordinal);
        Assert.EndsWith("mm but the X axis stops at 0.0992 mm (its Maximum Position)", ex.Message, StringComparison.Ordinal);
        await stage.X.DidNotReceiveWithAnyArgs().HomeAsync(Arg.Any<CancellationToken>());
        await stage.Y.DidNotReceiveWithAnyArgs().HomeAsync(Arg.Any<CancellationToken>());
    }

    /// <summary>The preflight of a raster job, with the program the engine runs (timed when its plan has a timing model).</summary>
    private static RunPreflight Preflight(IStage stage, ILaserGate gate, PreparedJob job, RunOptions options) =>
        new(stage, gate, EngraveJob.Of(job).Parts[0], job.Program(), job.Spec.Process, job.Spec.Profile, job.Plan.Timing, TravelSpeedData, AccelerationData, options);

    private static (IStage Stage, ILaserGate Gate) Fakes(AxisIdentity x, AxisIdentity y)
    {
        var gate = Substitute.For<ILaserGate>();
        gate.IdentifyAsync(Arg.Any<CancellationToken>()).ReturnsForAnyArgs("PICGATE 1.0");
        var stage = Substitute.For<IStage>();
        foreach (var (identity, number) in new[] { (x, (byte)1), (y, (byte)2) })
        {
            var axis = Substitute.For<IStageAxis>();
            axis.DeviceNumber.Returns(number);
            axis.IdentifyAsync(Arg.Any<CancellationToken>()).ReturnsForAnyArgs(identity with { DeviceNumber = number });
            if (number == 1)
            {
                stage.X.Returns(axis);
            }
            else
            {
                stage.Y.Returns(axis);
            }
        }

        return (stage, gate);
    }
}
