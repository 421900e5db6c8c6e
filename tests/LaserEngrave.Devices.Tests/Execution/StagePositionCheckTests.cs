using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Planning;
using LaserEngrave.Devices.Abstractions;
using LaserEngrave.Devices.Execution;
using NSubstitute;

namespace LaserEngrave.Devices.Tests.Execution;

/// <summary>The stroke's position checks alone (<see cref="StagePositionCheck"/>): the laser stays off until the stage is seen where its plan says.</summary>
public class StagePositionCheckTests
{
    private static readonly TimedSwitching Timing = TimedSwitching.For(ProcessSettings.Default, MachineProfile.Default, MachineProfile.Default.X.MicrostepUm);

    [Fact]
    public async Task ConfirmMovingAsync_QueryUnansweredByTheSwitchOn_FaultsAsATimingDoubt()
    {
        var run = new FakeRun { Answers = false };
        var position = Make(run);
        var query = position.Arrival(new TaskCompletionSource<long>().Task);

        await Assert.ThrowsAsync<DeviceException>(() => position.ConfirmMovingAsync([], query, 0, 0, 1, Timing, 0.1, TestContext.Current.CancellationToken));

        Assert.Equal([("the X axis did not answer the position query before the laser was to come on", true)], run.Faults);
    }

    [Fact]
    public async Task ConfirmMovingAsync_StageStillAtItsStart_FaultsAndTheLaserStaysOff()
    {
        // Answered at once, but 0 microsteps on from the start a frame after the move: the stage is not moving as planned.
        var run = new FakeRun { Answers = true, Now = 0 };
        var position = Make(run);
        var query = position.Arrival(Task.FromResult(1000L));
        run.Now = 1.0;

        await Assert.ThrowsAsync<DeviceException>(() => position.ConfirmMovingAsync([], query, 0, 1000, 1, Timing, 0, TestContext.Current.CancellationToken));

        var (reason, recoverable) = Assert.Single(run.Faults);
        Assert.False(recoverable);
        Assert.StartsWith("the X axis reported 1000 microsteps just after starting its stroke", reason, StringComparison.Ordinal);
    }

    [Fact]
    public void Arrival_ReplyCompletes_StampsItOnTheRunClock()
    {
        var run = new FakeRun { Now = 0.25 };
        var reply = new TaskCompletionSource<long>();
        var arrived = Make(run).Arrival(reply.Task);
        Assert.True(double.IsNaN(arrived.Seconds));

        run.Now = 0.5;
        reply.SetResult(7);

        Assert.Equal(0.5, arrived.Seconds);
    }

    private static StagePositionCheck Make(FakeRun run) =>
        new(Substitute.For<IStage>(), MotionData.Of(ProcessSettings.Default, PlanStrategy.Optimized, MachineProfile.Default.X.MicrostepUm), MachineProfile.Default.X.TravelMicrosteps, run);

    private sealed class FakeRun : IStagePositionCheckRun
    {
        public bool Answers { get; init; }

        public double Now { get; set; }

        public List<(string Reason, bool Recoverable)> Faults { get; } = [];

        public double RunSeconds => Now;

        public double LatencyScale => 1;

        public void ThrowIfAborted()
        {
        }

        public DeviceException Fault(string reason, bool recoverable)
        {
            Faults.Add((reason, recoverable));
            return new DeviceException(reason);
        }

        public Task DelayUntilAsync(double seconds, CancellationToken token) => Task.CompletedTask;

        public void Watch(Task reply, double expectedSeconds, string what)
        {
        }

        public Task<double> WrittenLateAsync(Task<long?> lineWritten, double plannedWrite) => Task.FromResult(0.0);

        public Task<bool> CompletesByAsync(Task task, double seconds, CancellationToken token) => Task.FromResult(Answers);

        public void GapFlown()
        {
        }

        public void LatencySeen(double scale)
        {
        }
    }
}
