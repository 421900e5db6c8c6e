using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Jobs;
using LaserEngrave.Core.Planning;
using LaserEngrave.Devices.Abstractions;
using LaserEngrave.Devices.Execution;
using LaserEngrave.Simulator;
using NSubstitute;
using NSubstitute.ExceptionExtensions;

namespace LaserEngrave.Devices.Tests.Execution;

/// <summary>Preflight: what it checks, fixes and refuses, on the simulator and with fakes.</summary>
public class PreflightTests
{
    private static readonly AxisIdentity Homed = new(1, 4212, 502, 0x80, 604_724);

    [Fact(Timeout = 60_000)]
    public async Task RunAsync_JobOutsideTheTravel_RefusesBeforeTouchingTheDevices()
    {
        var stage = Substitute.For<IStage>();
        var gate = Substitute.For<ILaserGate>();
        var job = TestJobs.FromMask(TestJobs.RandomMask(1, 8, 8), 5, new PlanOptions(), new OriginMm(58, 10));
        var executor = new RunExecutor(stage, gate, job);

        var ex = await Assert.ThrowsAsync<PreflightException>(() => executor.RunAsync(TestContext.Current.CancellationToken));

        // The job rules' sentence, as the command line, the app's origin field and its Start say it (issue 35).
        Assert.Equal("the job (5 x 5 mm at origin 58, 10 mm) does not fit the stage's travel (60 x 60 mm): move the origin or make it smaller", ex.Message);
        Assert.DoesNotContain('\n', ex.Message);
        Assert.Equal(RunState.Failed, executor.State);
        await gate.DidNotReceiveWithAnyArgs().SetFrequencyAsync(Arg.Any<int>(), Arg.Any<CancellationToken>());
        await stage.X.DidNotReceiveWithAnyArgs().MoveAbsoluteAsync(Arg.Any<long>(), Arg.Any<CancellationToken>());
    }

    [Theory(Timeout = 60_000)]
    [InlineData(10.0, 4.0, 50.0, "burn speed 10 mm/s is outside")]
    [InlineData(1.0, 4.5, 50.0, "travel speed 4.5 mm/s is outside")]
    [InlineData(0.0004, 4.0, 50.0, "burn speed 0.0004 mm/s is outside")]
    [InlineData(1.0, 4.0, 500.0, "acceleration 500 mm/s² is outside")]
    public async Task RunAsync_SpeedTheStageCannotRun_Refuses(double burnMmPerS, double travelMmPerS, double accelerationMmPerS2, string expected)
    {
        var stage = Substitute.For<IStage>();
        var gate = Substitute.For<ILaserGate>();
        var process = ProcessSettings.Default with { BurnSpeedMmPerS = burnMmPerS, TravelSpeedMmPerS = travelMmPerS, AccelerationMmPerS2 = accelerationMmPerS2 };
        var job = TestJobs.FromMask(TestJobs.RandomMask(1, 8, 8), 1, new PlanOptions(), process: process);

        var ex = await Assert.ThrowsAsync<PreflightException>(() => new RunExecutor(stage, gate, job).RunAsync(TestContext.Current.CancellationToken));

        Assert.StartsWith(expected, ex.Message, StringComparison.Ordinal);
        await gate.DidNotReceiveWithAnyArgs().SetFrequencyAsync(Arg.Any<int>(), Arg.Any<CancellationToken>());
    }

    [Fact(Timeout = 60_000)]
    public async Task RunAsync_GateSilent_RefusesNamingTheGate()
    {
        await using var run = SimulatedRun.Create(new SimulatorOptions { FaultSpec = "silent:gate" });
        var job = TestJobs.FromMask(TestJobs.RandomMask(1, 8, 4), 1, new PlanOptions());

        var ex = await Assert.ThrowsAsync<PreflightException>(() => run.Do(() => run.Executor(job).RunAsync(TestContext.Current.CancellationToken)));

        Assert.StartsWith("the laser gate does not answer as it should: ", ex.Message, StringComparison.Ordinal);
        Assert.Contains("did not acknowledge '*IDN?'", ex.Message, StringComparison.Ordinal);
        Assert.False(run.Machine.Stage.X.IsHomed, "the stage moved although the gate is silent");
    }

    [Fact(Timeout = 60_000)]
    public async Task RunAsync_AxisNotAnswering_RefusesNamingTheAxis()
    {
        await using var run = SimulatedRun.Create(new SimulatorOptions { FaultSpec = "silent:stage:device=2" });
        var job = TestJobs.FromMask(TestJobs.RandomMask(1, 8, 4), 1, new PlanOptions());

        var ex = await Assert.ThrowsAsync<PreflightException>(() => run.Do(() => run.Executor(job).RunAsync(TestContext.Current.CancellationToken)));

        Assert.StartsWith("the Y axis (device 2) does not answer as it should: ", ex.Message, StringComparison.Ordinal);
        Assert.False(run.Machine.Gate.IsFiring);
    }

    [Fact(Timeout = 60_000)]
    public async Task RunAsync_AutoReplyDisabled_ClearsTheBitAndRuns()
    {
        await using var run = SimulatedRun.Create(new SimulatorOptions { DeviceMode = 1 });
        var job = TestJobs.FromMask(TestJobs.RandomMask(2, 8, 4), 1, new PlanOptions());

        var result = await run.Do(() => run.Executor(job).RunAsync(TestContext.Current.CancellationToken));

        Assert.True(result.Outcome == RunOutcome.Completed, $"{result.Outcome}: {result.FaultMessage}");
        Assert.Equal(0, run.Machine.Stage.X.DeviceMode & 1);
        Assert.Equal(0, run.Machine.Stage.Y.DeviceMode & 1);
        Assert.False(result.Machine!.X.AutoReplyDisabled);
        Assert.True(run.Analyze(job).Burned.ContentEquals(job.Mask));
    }

    [Fact(Timeout = 60_000)]
    public async Task RunAsync_AutoReplyDisabledAndNoFix_Refuses()
    {
        await using var run = SimulatedRun.Create(new SimulatorOptions { DeviceMode = 1 });
        var job = TestJobs.FromMask(TestJobs.RandomMask(2, 8, 4), 1, new PlanOptions());

        var ex = await Assert.ThrowsAsync<PreflightException>(() => run.Do(() => run.Executor(job, new RunOptions { FixAutoReply = false }).RunAsync(TestContext.Current.CancellationToken)));

        Assert.Contains("the X axis (device 1) has auto-reply disabled", ex.Message, StringComparison.Ordinal);
    }

    [Fact(Timeout = 60_000)]
    public async Task RunAsync_NotHomed_HomesBothAxesFirst()
    {
        await using var run = SimulatedRun.Create();
        var devices = new RecordingDevices(run.Stage, run.Gate);
        var job = TestJobs.FromMask(TestJobs.RandomMask(2, 8, 4), 1, Untimed);

        var result = await run.Do(() => new RunExecutor(devices.Stage, devices.Gate, job, run.Time).RunAsync(TestContext.Current.CancellationToken));
        var log = devices.Log.ToList();

        Assert.True(result.Outcome == RunOutcome.Completed, $"{result.Outcome}: {result.FaultMessage}");
        Assert.Equal(["X home", "Y home"], log.Where(e => e.EndsWith("home", StringComparison.Ordinal)).Order());
        Assert.True(log.IndexOf("X home") < log.FindIndex(e => e.StartsWith("X move", StringComparison.Ordinal)));
    }

    [Fact(Timeout = 60_000)]
    public async Task RunAsync_HomedAndHomeAsked_HomesAgain()
    {
        var stage = FakeStage(Homed);
        var gate = Substitute.For<ILaserGate>();
        gate.IdentifyAsync(Arg.Any<CancellationToken>()).ReturnsForAnyArgs("PICGATE 1.0");
        var job = TestJobs.FromMask(TestJobs.Mask("#"), 0.1, Untimed);

        var result = await new RunExecutor(stage, gate, job, options: new RunOptions { Home = true }).RunAsync(TestContext.Current.CancellationToken);

        Assert.True(result.Outcome == RunOutcome.Completed, $"{result.Outcome}: {result.FaultMessage}");
        await stage.X.Received(1).HomeAsync(Arg.Any<CancellationToken>());
        await stage.Y.Received(1).HomeAsync(Arg.Any<CancellationToken>());
    }

    [Fact(Timeout = 60_000)]
    public async Task RunAsync_HomedAlready_DoesNotHome()
    {
        var stage = FakeStage(Homed);
        var gate = Substitute.For<ILaserGate>();
        gate.IdentifyAsync(Arg.Any<CancellationToken>()).ReturnsForAnyArgs("PICGATE 1.0");
        var job = TestJobs.FromMask(TestJobs.Mask("#"), 0.1, Untimed);

        var result = await new RunExecutor(stage, gate, job).RunAsync(TestContext.Current.CancellationToken);

        Assert.True(result.Outcome == RunOutcome.Completed, $"{result.Outcome}: {result.FaultMessage}");
        await stage.X.DidNotReceiveWithAnyArgs().HomeAsync(Arg.Any<CancellationToken>());
        await gate.Received().SetWatchdogAsync(1000, Arg.Any<CancellationToken>());
        await gate.Received().SetFrequencyAsync(1000, Arg.Any<CancellationToken>());
    }

    [Fact(Timeout = 60_000)]
    public async Task RunAsync_AxisShorterThanTheJob_RefusesNamingTheAxis()
    {
        var stage = FakeStage(Homed with { MaximumPosition = 50_000 });
        var gate = Substitute.For<ILaserGate>();
        gate.IdentifyAsync(Arg.Any<CancellationToken>()).ReturnsForAnyArgs("PICGATE 1.0");
        var job = TestJobs.FromMask(TestJobs.Mask("#"), 0.1, new PlanOptions());

        var ex = await Assert.ThrowsAsync<PreflightException>(() => new RunExecutor(stage, gate, job).RunAsync(TestContext.Current.CancellationToken));

        Assert.StartsWith("the job reaches X = 10.1 mm but the X axis stops at 4.9609 mm", ex.Message, StringComparison.Ordinal);
    }

    [Fact(Timeout = 60_000)]
    public async Task RunAsync_FakeAxisWithAutoReplyDisabled_Refuses()
    {
        var stage = FakeStage(Homed with { DeviceMode = 0x81 });
        var gate = Substitute.For<ILaserGate>();
        gate.IdentifyAsync(Arg.Any<CancellationToken>()).ReturnsForAnyArgs("PICGATE 1.0");
        var job = TestJobs.FromMask(TestJobs.Mask("#"), 0.1, new PlanOptions());

        var ex = await Assert.ThrowsAsync<PreflightException>(() => new RunExecutor(stage, gate, job).RunAsync(TestContext.Current.CancellationToken));

        Assert.Contains("auto-reply disabled", ex.Message, StringComparison.Ordinal);
    }

    [Fact(Timeout = 60_000)]
    public async Task RunAsync_GateTimesOut_RefusesAfterAskingTwice()
    {
        var stage = FakeStage(Homed);
        var gate = Substitute.For<ILaserGate>();
        gate.IdentifyAsync(Arg.Any<CancellationToken>()).ThrowsAsyncForAnyArgs(new DeviceTimeoutException("laser gate on COM4 did not acknowledge '*IDN?' within 500 ms"));
        var job = TestJobs.FromMask(TestJobs.Mask("#"), 0.1, new PlanOptions());

        var ex = await Assert.ThrowsAsync<PreflightException>(() => new RunExecutor(stage, gate, job).RunAsync(TestContext.Current.CancellationToken));

        Assert.Equal("the laser gate does not answer as it should: laser gate on COM4 did not acknowledge '*IDN?' within 500 ms", ex.Message);
        await gate.Received(2).IdentifyAsync(Arg.Any<CancellationToken>());
        await stage.X.DidNotReceiveWithAnyArgs().IdentifyAsync(Arg.Any<CancellationToken>());
    }

    [Fact(Timeout = 60_000)]
    public async Task RunAsync_ResumePointNotInThePlan_Refuses()
    {
        var stage = FakeStage(Homed);
        var gate = Substitute.For<ILaserGate>();
        gate.IdentifyAsync(Arg.Any<CancellationToken>()).ReturnsForAnyArgs("PICGATE 1.0");
        var job = TestJobs.FromMask(TestJobs.Mask("#"), 0.1, new PlanOptions());

        var ex = await Assert.ThrowsAsync<PreflightException>(
            () => new RunExecutor(stage, gate, job, options: new RunOptions { ResumeFrom = new RunStopPoint(0, 99, null, null) }).RunAsync(TestContext.Current.CancellationToken));

        Assert.Equal("the resume point (row 0, move 99) is not in this job's plan of 3 moves", ex.Message);
    }

    // An instant fake stage cannot show itself moving to timed switching's position query: these tests run the plan step by step.
    [Fact(Timeout = 60_000)]
    public async Task RunAsync_FirmwareTheManualDoesNotCoverAndTimedPlan_RefusesNamingAxisFirmwareAndWhatIsMissing()
    {
        var stage = FakeStage(Homed with { FirmwareVersion = 610 });
        var gate = Substitute.For<ILaserGate>();
        gate.IdentifyAsync(Arg.Any<CancellationToken>()).ReturnsForAnyArgs("PICGATE 1.0");
        var job = TestJobs.FromMask(TestJobs.Mask("#.#"), 0.3, new PlanOptions());

        var ex = await Assert.ThrowsAsync<PreflightException>(() => new RunExecutor(stage, gate, job).RunAsync(TestContext.Current.CancellationToken));

        Assert.StartsWith("the X axis (device 1) has firmware 6.10", ex.Message, StringComparison.Ordinal);
        Assert.Contains("Set Target Speed during a move", ex.Message, StringComparison.Ordinal);
        Assert.Contains("--strategy paper", ex.Message, StringComparison.Ordinal);
        await stage.X.DidNotReceiveWithAnyArgs().HomeAsync(Arg.Any<CancellationToken>());
        await gate.DidNotReceiveWithAnyArgs().SetFrequencyAsync(Arg.Any<int>(), Arg.Any<CancellationToken>());
    }

    [Fact(Timeout = 60_000)]
    public async Task RunAsync_FirmwareTheManualDoesNotCoverAndStepByStepPlan_Runs()
    {
        var stage = FakeStage(Homed with { FirmwareVersion = 610 });
        var gate = Substitute.For<ILaserGate>();
        gate.IdentifyAsync(Arg.Any<CancellationToken>()).ReturnsForAnyArgs("PICGATE 1.0");
        var job = TestJobs.FromMask(TestJobs.Mask("#"), 0.1, Untimed);

        var result = await new RunExecutor(stage, gate, job).RunAsync(TestContext.Current.CancellationToken);

        Assert.True(result.Outcome == RunOutcome.Completed, $"{result.Outcome}: {result.FaultMessage}");
    }

    private static PlanOptions Untimed => new() { Strategy = PlanStrategy.Paper };

    /// <summary>A stage whose axes identify as <paramref name="identity"/> and arrive wherever they are sent.</summary>
    private static IStage FakeStage(AxisIdentity identity)
    {
        var stage = Substitute.For<IStage>();
        foreach (var (axis, number) in new[] { (Substitute.For<IStageAxis>(), (byte)1), (Substitute.For<IStageAxis>(), (byte)2) })
        {
            axis.DeviceNumber.Returns(number);
            axis.IdentifyAsync(Arg.Any<CancellationToken>()).ReturnsForAnyArgs(identity with { DeviceNumber = number });
            axis.MoveAbsoluteAsync(Arg.Any<long>(), Arg.Any<CancellationToken>()).ReturnsForAnyArgs(call => call.Arg<long>());
            if (number == 1)
            {
                stage.X.Returns(axis);
            }
            else
            {
                stage.Y.Returns(axis);
            }
        }

        return stage;
    }
}
