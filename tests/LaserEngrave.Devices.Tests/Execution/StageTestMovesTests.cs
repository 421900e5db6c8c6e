using LaserEngrave.Core.Planning;
using LaserEngrave.Devices.Execution;
using LaserEngrave.Simulator.Burn;

namespace LaserEngrave.Devices.Tests.Execution;

/// <summary>Jog, go to, origin, home, frame and test fire on the in-process simulator.</summary>
public class StageTestMovesTests
{
    private static readonly BurnGrid AnyGrid = new(0, 0, 100, 1, 1);

    [Fact(Timeout = 60_000)]
    public async Task JogAsync_XByAStep_MovesOnlyXByTheRoundedStep()
    {
        await using var run = SimulatedRun.Create();
        var moves = run.TestMoves();
        var ct = TestContext.Current.CancellationToken;
        await run.Do(() => moves.GoToAsync(10, 20, ct));

        var after = await run.Do(() => moves.JogAsync(StageAxisName.X, 100, ct));

        Assert.Equal(new StagePosition(100_787 + 1008, 201_575), after);
        Assert.Equal(after, await run.Do(() => moves.GetPositionAsync(ct)));
        Assert.Equal(0, run.Machine.Recorder.Analyze(AnyGrid).LaserOnSeconds);
    }

    [Fact(Timeout = 60_000)]
    public async Task JogAsync_PastTheTravel_RefusesWithoutMoving()
    {
        await using var run = SimulatedRun.Create();
        var moves = run.TestMoves();
        var ct = TestContext.Current.CancellationToken;
        var before = await run.Do(() => moves.HomeAsync(ct));

        var ex = await Assert.ThrowsAsync<TestMoveException>(() => run.Do(() => moves.JogAsync(StageAxisName.Y, -100, ct)));

        Assert.Equal("y -0.1 mm is outside the stage travel 0..60 mm", ex.Message);
        Assert.Equal(before, await run.Do(() => moves.GetPositionAsync(ct)));
    }

    [Theory(Timeout = 60_000)]
    [InlineData(61, 10, "x 61 mm is outside the stage travel 0..60 mm")]
    [InlineData(10, -1, "y -1 mm is outside the stage travel 0..60 mm")]
    [InlineData(double.NaN, 1, "position NaN,1 mm is not a number")]
    public async Task GoToAsync_BadTarget_RefusesInOneLine(double xMm, double yMm, string expected)
    {
        await using var run = SimulatedRun.Create();

        var ex = await Assert.ThrowsAsync<TestMoveException>(() => run.Do(() => run.TestMoves().GoToAsync(xMm, yMm, TestContext.Current.CancellationToken)));

        Assert.Equal(expected, ex.Message);
        Assert.False(run.Machine.Stage.X.IsMoving);
    }

    [Fact(Timeout = 60_000)]
    public async Task GoToOriginAsync_Job_ArrivesAtTheImagesTopLeftCorner()
    {
        await using var run = SimulatedRun.Create();
        var job = TestJobs.FromMask(TestJobs.RandomMask(1, 8, 4), 2, new PlanOptions());

        var at = await run.Do(() => run.TestMoves().GoToOriginAsync(job.Plan.Geometry, TestContext.Current.CancellationToken));

        Assert.Equal(new StagePosition(job.Plan.Geometry.EdgeX(0), job.Plan.Geometry.EdgeY(0)), at);
        Assert.Equal((at.XMicrosteps, at.YMicrosteps), (run.Machine.Stage.X.Position, run.Machine.Stage.Y.Position));
    }

    [Fact(Timeout = 60_000)]
    public async Task HomeAsync_Anywhere_HomesBothAxes()
    {
        await using var run = SimulatedRun.Create();
        var moves = run.TestMoves();
        var ct = TestContext.Current.CancellationToken;
        await run.Do(() => moves.GoToAsync(5, 5, ct));

        var at = await run.Do(() => moves.HomeAsync(ct));

        Assert.Equal(new StagePosition(0, 0), at);
        Assert.True(run.Machine.Stage.X.IsHomed && run.Machine.Stage.Y.IsHomed);
    }

    [Fact(Timeout = 60_000)]
    public async Task FrameAsync_LaserOff_TracesTheRectangleWithoutFiring()
    {
        await using var run = SimulatedRun.Create();
        var devices = new RecordingDevices(run.Stage, run.Gate);
        var moves = new StageTestMoves(devices.Stage, devices.Gate, run.Machine.Profile, timeProvider: run.Time);
        var job = TestJobs.FromMask(TestJobs.RandomMask(1, 8, 4), 2, new PlanOptions());
        var g = job.Plan.Geometry;

        var end = await run.Do(() => moves.FrameAsync(g, visibleFrequencyHz: null, TestContext.Current.CancellationToken));

        Assert.Equal(new StagePosition(g.EdgeX(0), g.EdgeY(0)), end);
        Assert.Equal(
            [$"X move {g.EdgeX(0)}", $"Y move {g.EdgeY(0)}", $"X move {g.EdgeX(8)}", $"Y move {g.EdgeY(4)}", $"X move {g.EdgeX(0)}", $"Y move {g.EdgeY(0)}"],
            devices.Log.Where(e => e.Contains(" move ", StringComparison.Ordinal)));
        Assert.DoesNotContain(devices.Log, e => e.StartsWith("laser 1", StringComparison.Ordinal));
        Assert.Equal(0, run.Machine.Recorder.Analyze(AnyGrid).LaserOnSeconds);
    }

    [Fact(Timeout = 60_000)]
    public async Task FrameAsync_Visible_FiresAtTheLowFrequencyAndEndsOff()
    {
        await using var run = SimulatedRun.Create();
        var job = TestJobs.FromMask(TestJobs.RandomMask(1, 8, 4), 4, new PlanOptions());

        await run.Do(() => run.TestMoves().FrameAsync(job.Plan.Geometry, visibleFrequencyHz: 20, TestContext.Current.CancellationToken));

        // 4 + 2 + 4 + 2 mm at 4 mm/s: about 3 s with the laser on, longer than the watchdog, so the keepalive works.
        Assert.InRange(run.Machine.Recorder.Analyze(AnyGrid).LaserOnSeconds, 3, 4);
        Assert.False(run.Machine.Gate.IsFiring);
        Assert.Equal(0, run.Machine.Gate.WatchdogTrips);
    }

    [Fact(Timeout = 60_000)]
    public async Task FirePulsesAsync_Burst_FiresForPulsesOverFrequencyAndEndsOff()
    {
        await using var run = SimulatedRun.Create();

        await run.Do(() => run.TestMoves().FirePulsesAsync(50, 1000, TestContext.Current.CancellationToken));

        Assert.InRange(run.Machine.Recorder.Analyze(AnyGrid).LaserOnSeconds, 0.049, 0.052);
        Assert.False(run.Machine.Gate.IsFiring);
    }

    [Fact(Timeout = 60_000)]
    public async Task FireForAsync_LongerThanTheWatchdog_FiresTheWholeTimeAndEndsOff()
    {
        await using var run = SimulatedRun.Create();

        await run.Do(() => run.TestMoves().FireForAsync(TimeSpan.FromSeconds(3), 1000, TestContext.Current.CancellationToken));

        Assert.InRange(run.Machine.Recorder.Analyze(AnyGrid).LaserOnSeconds, 3, 3.05);
        Assert.False(run.Machine.Gate.IsFiring);
        Assert.Equal(0, run.Machine.Gate.WatchdogTrips);
    }

    [Theory(Timeout = 60_000)]
    [InlineData(0, 1000, "test fire of 0 pulses: must be 1..1000000 pulses (the laser gate's burst range)")]
    [InlineData(1_000_001, 1000, "test fire of 1000001 pulses: must be 1..1000000 pulses (the laser gate's burst range)")]
    [InlineData(10, 0, "test fire at 0 Hz: the frequency must be above 0")]
    public async Task FirePulsesAsync_OutsideTheRules_RefusedWithTheRulesSentenceLaserNeverOn(int pulses, int frequencyHz, string expected)
    {
        await using var run = SimulatedRun.Create();

        var ex = await Assert.ThrowsAsync<TestMoveException>(() => run.Do(() => run.TestMoves().FirePulsesAsync(pulses, frequencyHz, TestContext.Current.CancellationToken)));

        Assert.Equal(expected, ex.Message);
        Assert.Equal(0, run.Machine.Recorder.Analyze(AnyGrid).LaserOnSeconds);
    }
}
