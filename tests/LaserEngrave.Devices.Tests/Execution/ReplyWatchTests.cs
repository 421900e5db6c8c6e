using LaserEngrave.Core.Planning;
using LaserEngrave.Devices.Abstractions;
using LaserEngrave.Devices.Execution;
using LaserEngrave.Devices.Tests.Fakes;
using LaserEngrave.Simulator.Timing;
using LaserEngrave.Wire.Scheduling;

namespace LaserEngrave.Devices.Tests.Execution;

/// <summary>The replies a timed run does not wait for, watched alone (<see cref="ReplyWatch"/>) on the simulation's virtual clock.</summary>
public class ReplyWatchTests
{
    private const double StallMarginMs = 20;
    private const string Stalled = "within 20 ms of its expected arrival (stalled, or its reply was lost)";

    [Fact(Timeout = 60_000)]
    public async Task Watch_ReplyPastItsDeadline_ReportedOnceAsAFaultAtTheDeadline()
    {
        using var time = new VirtualTimeProvider();
        var run = new FakeRun(time);
        var replies = new ReplyWatch(time, StallMarginMs, run);
        double faultedAt = 0;

        await time.RunTestAsync(async () =>
        {
            var watched = replies.Watch(new TaskCompletionSource().Task, 1.0, "the end of a travel (X)", axis: "X");
            await watched.Done.Task;
            faultedAt = run.RunSeconds;
            await time.SettleAsync();
        });

        Assert.Equal([$"the stage did not report the end of a travel (X) {Stalled}"], run.Faults);
        Assert.Equal(1.02, faultedAt, 9);
        Assert.Equal(0, run.SwitchOffsFailed);
    }

    [Fact(Timeout = 60_000)]
    public async Task Watch_ReplyWithinTheStallMargin_ReportsNothing()
    {
        using var time = new VirtualTimeProvider();
        var run = new FakeRun(time);
        var replies = new ReplyWatch(time, StallMarginMs, run);

        await time.RunTestAsync(async () =>
        {
            var watched = replies.Watch(ReplyAfter(time, 1.015), 1.0, "Set Target Speed (X)");
            await watched.Done.Task;
            Assert.Empty(replies.Unsettled());
        });

        Assert.Empty(run.Faults);
    }

    [Fact(Timeout = 60_000)]
    public async Task Watch_SuccessorReportsItsEnd_SettlesAPredecessorNeverReported()
    {
        using var time = new VirtualTimeProvider();
        var run = new FakeRun(time);
        var replies = new ReplyWatch(time, StallMarginMs, run);

        await time.RunTestAsync(async () =>
        {
            var first = replies.Watch(new TaskCompletionSource().Task, 1.0, "the end of a stroke (X)", axis: "X");
            var second = replies.Watch(ReplyAfter(time, 1.5), 2.0, "the end of a travel (X)", axis: "X");
            Assert.Same(second, first.Successor);
            await first.Done.Task;
            Assert.True(second.Done.Task.IsCompleted);
            Assert.Empty(replies.Unsettled());
        });

        Assert.Empty(run.Faults);
    }

    [Fact(Timeout = 60_000)]
    public async Task Watch_SuccessorNeverReportsEither_FaultsOnceForTheSuccessor()
    {
        using var time = new VirtualTimeProvider();
        var run = new FakeRun(time);
        var replies = new ReplyWatch(time, StallMarginMs, run);

        await time.RunTestAsync(async () =>
        {
            var first = replies.Watch(new TaskCompletionSource().Task, 1.0, "the end of a stroke (X)", axis: "X");
            replies.Watch(new TaskCompletionSource().Task, 2.0, "the end of a travel (X)", axis: "X");
            await first.Done.Task;
        });

        Assert.Equal([$"the stage did not report the end of a travel (X) {Stalled}"], run.Faults);
    }

    [Fact(Timeout = 60_000)]
    public async Task Watch_DeadlineMovedLaterWhileWaiting_WaitsForTheNewOne()
    {
        using var time = new VirtualTimeProvider();
        var run = new FakeRun(time);
        var replies = new ReplyWatch(time, StallMarginMs, run);

        await time.RunTestAsync(async () =>
        {
            var watched = replies.Watch(ReplyAfter(time, 1.5), 1.0, "the end of a stroke (X)", axis: "X");
            await PreciseDelay.DelayAsync(time, TimeSpan.FromSeconds(0.5), CancellationToken.None);

            // A stroke found behind its plan ends that much later.
            watched.Deadline += 1.0;
            await watched.Done.Task;
        });

        Assert.Empty(run.Faults);
    }

    [Fact(Timeout = 60_000)]
    public async Task Watch_SwitchOffUnanswered_MarksItFailedAndFaultsInTheGatesWords()
    {
        using var time = new VirtualTimeProvider();
        var run = new FakeRun(time);
        var replies = new ReplyWatch(time, StallMarginMs, run);

        await time.RunTestAsync(async () =>
        {
            var watched = replies.Watch(new TaskCompletionSource().Task, 1.0, "the laser gate did not acknowledge the switch-off", gate: true, switchOff: true);
            await watched.Done.Task;
        });

        Assert.Equal(["the laser gate did not acknowledge the switch-off within 20 ms of its expected arrival"], run.Faults);
        Assert.Equal(1, run.SwitchOffsFailed);
    }

    [Fact(Timeout = 60_000)]
    public async Task Watch_ReplyFailed_FaultsWithTheDevicesMessage()
    {
        using var time = new VirtualTimeProvider();
        var run = new FakeRun(time);
        var replies = new ReplyWatch(time, StallMarginMs, run);

        await time.RunTestAsync(async () =>
        {
            var watched = replies.Watch(Task.FromException(new DeviceException("device 1 replied error 255 to Move Absolute")), 1.0, "the end of a travel (X)", axis: "X");
            await watched.Done.Task;
        });

        Assert.Equal(["device 1 replied error 255 to Move Absolute"], run.Faults);
    }

    [Fact(Timeout = 60_000)]
    public async Task AllSettledAsync_AReplyMissing_ThrowsTheRunsFaultAfterItsDeadline()
    {
        using var time = new VirtualTimeProvider();
        var run = new FakeRun(time);
        var replies = new ReplyWatch(time, StallMarginMs, run);
        DeviceException? thrown = null;

        await time.RunTestAsync(async () =>
        {
            replies.Watch(ReplyAfter(time, 0.5), 1.0, "Set Target Speed (X)");
            replies.Watch(new TaskCompletionSource().Task, 1.0, "the end of a travel (Y)", axis: "Y");
            thrown = await VirtualTime.ThrowsAsync<DeviceException>(replies.AllSettledAsync(CancellationToken.None));
        });

        Assert.Equal($"the stage did not report the end of a travel (Y) {Stalled}", thrown!.Message);
        Assert.All(run.Faults, f => Assert.Equal(thrown.Message, f));
    }

    [Fact(Timeout = 60_000)]
    public async Task AllSettledAsync_EveryReplyIn_ReturnsAndClearLeavesNothing()
    {
        using var time = new VirtualTimeProvider();
        var run = new FakeRun(time);
        var replies = new ReplyWatch(time, StallMarginMs, run);

        await time.RunTestAsync(async () =>
        {
            replies.Watch(ReplyAfter(time, 0.5), 1.0, "Set Target Speed (X)");
            replies.Watch(ReplyAfter(time, 0.9), 1.0, "the end of a travel (Y)", axis: "Y");
            await replies.AllSettledAsync(CancellationToken.None);
            replies.Clear();
            Assert.Empty(replies.Unsettled());
        });

        Assert.Empty(run.Faults);
    }

    [Theory(Timeout = 60_000)]
    [InlineData(1.04)]
    [InlineData(1.12)]
    public async Task Watch_ReplyRead20To100MsLateWhileBytesAreArriving_ReportsNothing(double readAt)
    {
        // A host stalled after the reply arrived: its bytes wait unread until readAt, past the deadline at 1.02 s.
        using var time = new VirtualTimeProvider();
        var run = new FakeRun(time);
        Task reply = new TaskCompletionSource().Task;
        var replies = new ReplyWatch(time, StallMarginMs, run) { Arriving = gate => !gate && run.RunSeconds >= 1.0 && !reply.IsCompleted };

        await time.RunTestAsync(async () =>
        {
            reply = ReplyAfter(time, readAt);
            var watched = replies.Watch(reply, 1.0, "the end of a travel (X)", axis: "X");
            await watched.Done.Task;
            Assert.True(reply.IsCompletedSuccessfully);
        });

        Assert.Empty(run.Faults);
    }

    [Fact(Timeout = 60_000)]
    public async Task Watch_ReplyLateWithNothingArriving_FaultsAtTheDeadline()
    {
        using var time = new VirtualTimeProvider();
        var run = new FakeRun(time);
        var replies = new ReplyWatch(time, StallMarginMs, run) { Arriving = _ => false };
        double faultedAt = 0;

        await time.RunTestAsync(async () =>
        {
            var watched = replies.Watch(ReplyAfter(time, 1.06), 1.0, "the end of a travel (X)", axis: "X");
            await watched.Done.Task;
            faultedAt = run.RunSeconds;
        });

        Assert.Equal([$"the stage did not report the end of a travel (X) {Stalled}"], run.Faults);
        Assert.Equal(1.02, faultedAt, 9);
    }

    [Fact(Timeout = 60_000)]
    public async Task Watch_BytesArrivingOnTheOtherLinkOnly_FaultsAtTheDeadline()
    {
        using var time = new VirtualTimeProvider();
        var run = new FakeRun(time);
        var replies = new ReplyWatch(time, StallMarginMs, run) { Arriving = gate => gate };

        await time.RunTestAsync(async () =>
        {
            var watched = replies.Watch(ReplyAfter(time, 1.06), 1.0, "the end of a travel (X)", axis: "X");
            await watched.Done.Task;
        });

        Assert.Equal([$"the stage did not report the end of a travel (X) {Stalled}"], run.Faults);
    }

    [Fact(Timeout = 60_000)]
    public async Task Watch_BytesArrivingButNeverTheReply_FaultsAfterTheGrace()
    {
        using var time = new VirtualTimeProvider();
        var run = new FakeRun(time);
        var replies = new ReplyWatch(time, StallMarginMs, run) { Arriving = _ => true };
        double faultedAt = 0;

        await time.RunTestAsync(async () =>
        {
            var watched = replies.Watch(new TaskCompletionSource().Task, 1.0, "the laser gate did not acknowledge the switch-on", gate: true);
            await watched.Done.Task;
            faultedAt = run.RunSeconds;
        });

        Assert.Equal(["the laser gate did not acknowledge the switch-on within 20 ms of its expected arrival"], run.Faults);
        Assert.InRange(faultedAt, 1.02 + ReplyWatch.ArrivingGrace.TotalSeconds, 1.02 + ReplyWatch.ArrivingGrace.TotalSeconds + 0.01);
    }

    [Fact(Timeout = 60_000)]
    public async Task AllSettledAsync_ReplyReadLateWhileBytesAreArriving_Returns()
    {
        using var time = new VirtualTimeProvider();
        var run = new FakeRun(time);
        Task reply = new TaskCompletionSource().Task;
        var replies = new ReplyWatch(time, StallMarginMs, run) { Arriving = _ => run.RunSeconds >= 1.0 && !reply.IsCompleted };

        await time.RunTestAsync(async () =>
        {
            reply = ReplyAfter(time, 1.08);
            replies.Watch(reply, 1.0, "the end of a travel (Y)", axis: "Y");
            await replies.AllSettledAsync(CancellationToken.None);
        });

        Assert.Empty(run.Faults);
    }

    [Fact(Timeout = 60_000)]
    public async Task Watch_StageReplyMissingPastTheGrace_ReportedAsATimingDoubtToGoOnFrom()
    {
        using var time = new VirtualTimeProvider();
        var run = new FakeRun(time);
        var replies = new ReplyWatch(time, StallMarginMs, run) { Arriving = _ => false };

        await time.RunTestAsync(async () =>
        {
            var watched = replies.Watch(ReplyAfter(time, 1.3), 1.0, "Set Target Speed (X)");
            await watched.Done.Task;
        });

        Assert.Equal([$"the stage did not report Set Target Speed (X) {Stalled}"], run.Faults);
        Assert.Equal([true], run.Recoverable);
    }

    [Fact(Timeout = 60_000)]
    public async Task Watch_GateReplyMissingPastTheGrace_ReportedAsAFaultNotADoubt()
    {
        using var time = new VirtualTimeProvider();
        var run = new FakeRun(time);
        var replies = new ReplyWatch(time, StallMarginMs, run) { Arriving = _ => false };

        await time.RunTestAsync(async () =>
        {
            var watched = replies.Watch(new TaskCompletionSource().Task, 1.0, "the laser gate did not acknowledge the switch-off", gate: true, switchOff: true);
            await watched.Done.Task;
        });

        Assert.Equal([false], run.Recoverable);
        Assert.Equal(1, run.SwitchOffsFailed);
    }

    [Fact(Timeout = 60_000)]
    public async Task Watch_StageReplyFailed_ReportedAsAFaultNotADoubt()
    {
        using var time = new VirtualTimeProvider();
        var run = new FakeRun(time);
        var replies = new ReplyWatch(time, StallMarginMs, run);

        await time.RunTestAsync(async () =>
        {
            var watched = replies.Watch(Task.FromException(new DeviceException("device 1 replied error 255 to Set Target Speed")), 1.0, "Set Target Speed (X)");
            await watched.Done.Task;
        });

        Assert.Equal([false], run.Recoverable);
    }

    [Fact(Timeout = 60_000)]
    public async Task AllSettledAsync_StageReplyMissing_ThrowsATimingDoubtToGoOnFrom()
    {
        using var time = new VirtualTimeProvider();
        var run = new FakeRun(time);
        var replies = new ReplyWatch(time, StallMarginMs, run);

        await time.RunTestAsync(async () =>
        {
            replies.Watch(new TaskCompletionSource().Task, 1.0, "the end of a travel (Y)", axis: "Y");
            await VirtualTime.ThrowsAsync<DeviceException>(replies.AllSettledAsync(CancellationToken.None));
        });

        Assert.NotEmpty(run.Recoverable);
        Assert.All(run.Recoverable, Assert.True);
    }

    private static async Task ReplyAfter(TimeProvider time, double seconds) =>
        await PreciseDelay.DelayAsync(time, TimeSpan.FromSeconds(seconds), CancellationToken.None);

    /// <summary>The run whose replies are watched: its clock from 0 and the faults reported to it.</summary>
    private sealed class FakeRun(TimeProvider time) : IReplyWatchRun
    {
        private readonly long _start = time.GetTimestamp();

        public List<string> Faults { get; } = [];

        public int SwitchOffsFailed { get; private set; }

        public double RunSeconds => time.GetElapsedTime(_start).TotalSeconds;

        public TimedSwitching? Timing => null;

        /// <summary>Whether each fault in <see cref="Faults"/> was reported as a timing doubt the session may go on from.</summary>
        public List<bool> Recoverable { get; } = [];

        public DeviceException Fault(string reason, bool recoverable = false)
        {
            Faults.Add(reason);
            Recoverable.Add(recoverable);
            return new DeviceException(reason);
        }

        public void SwitchOffFailed(Task reply) => SwitchOffsFailed++;
    }
}
