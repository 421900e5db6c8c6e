using LaserEngrave.Devices.Scheduling;
using LaserEngrave.App.Services;
using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Jobs;
using LaserEngrave.Devices.Execution;
using LaserEngrave.Simulator;
using RunProgress = LaserEngrave.App.Services.RunProgress;

namespace LaserEngrave.App.Tests.Services;

/// <summary>The app's run service on the in-process simulator in virtual time.</summary>
public sealed class ExecutorRunServiceTests
{
    private static CancellationToken Token => TestContext.Current.CancellationToken;

    private static async Task<(RunResult Result, List<RunProgress> Progress, IMachineConnection Machine)> RunAsync(int passes, bool abortAfterFirstMove = false)
    {
        using var folder = TestFiles.NewFolder();
        var job = PreparedJob.Prepare(new JobSpec { ImagePath = TestFiles.WriteChecker(folder.Path, 8, 4), Size = SizeSpec.Width(0.8), Origin = new OriginMm(0.5, 0.5) });
        var machine = await new MachineConnectionFactory(new SimulatorOptions()).ConnectAsync(MachineChoice.Simulator, MachineProfile.Default, Token);
        var reports = new List<RunProgress>();
        using var abort = CancellationTokenSource.CreateLinkedTokenSource(Token);
        var progress = new SynchronousProgress(p =>
        {
            lock (reports)
            {
                reports.Add(p);
            }

            if (abortAfterFirstMove && p.MovesDone > 0)
            {
                abort.Cancel();
            }
        });
        var request = new RunRequest(job, machine.Stage, machine.Gate, passes, new RunPauseGate()) { TimeProvider = machine.TimeProvider };
        var run = new ExecutorRunService().RunAsync(request, progress, abort.Token);
        var result = await run.WaitAsync(TimeSpan.FromSeconds(60), Token);
        return (result, reports, machine);
    }

    [Fact]
    public async Task RunAsync_TwoPasses_BothCompletedWithEveryMove()
    {
        var (result, progress, machine) = await RunAsync(passes: 2);
        await using var _ = machine;

        Assert.Equal(RunOutcome.Completed, result.Outcome);
        var last = progress[^1];
        Assert.Equal((2, last.MovesTotal), (last.Pass, last.MovesDone));
        Assert.Contains(progress, p => p.Pass == 1 && p.MovesDone == p.MovesTotal);
        Assert.False((await TaskRunner.For(machine.TimeProvider).Run(() => machine.Gate.GetStateAsync(Token))).Firing);
    }

    [Fact]
    public async Task RunAsync_TwoPasses_TimesAndLaserOnAddUp()
    {
        var (single, _, first) = await RunAsync(passes: 1);
        await using var __ = first;
        var (twice, _, second) = await RunAsync(passes: 2);
        await using var _ = second;

        Assert.Equal(2 * single.EstimatedSeconds, twice.EstimatedSeconds, 6);
        Assert.InRange(twice.LaserOnSeconds, 1.9 * single.LaserOnSeconds, 2.1 * single.LaserOnSeconds);
        Assert.InRange(twice.EngravingDuration.TotalSeconds, 1.9 * single.EngravingDuration.TotalSeconds, 2.1 * single.EngravingDuration.TotalSeconds);
    }

    [Fact]
    public async Task RunAsync_Aborted_AbortedResultLaserOff()
    {
        var (result, _, machine) = await RunAsync(passes: 1, abortAfterFirstMove: true);
        await using var _ = machine;

        Assert.Equal(RunOutcome.Aborted, result.Outcome);
        Assert.True(result.RunsDone < result.RunsTotal);
        Assert.True(result.LaserOffConfirmed);
        Assert.False((await TaskRunner.For(machine.TimeProvider).Run(() => machine.Gate.GetStateAsync(Token))).Firing);
    }

    [Fact]
    public async Task RunAsync_ResumeFromAnAbortedRun_FinishesOnlyThatPassFromItsStopPoint()
    {
        using var folder = TestFiles.NewFolder();
        var job = PreparedJob.Prepare(new JobSpec { ImagePath = TestFiles.WriteChecker(folder.Path, 8, 4), Size = SizeSpec.Width(0.8), Origin = new OriginMm(0.5, 0.5) });
        await using var machine = await new MachineConnectionFactory(new SimulatorOptions()).ConnectAsync(MachineChoice.Simulator, MachineProfile.Default, Token);
        using var abort = CancellationTokenSource.CreateLinkedTokenSource(Token);
        var first = new RunRequest(job, machine.Stage, machine.Gate, 1, new RunPauseGate()) { TimeProvider = machine.TimeProvider };
        var aborted = await new ExecutorRunService().RunAsync(first, new SynchronousProgress(p =>
        {
            if (p.MovesDone > 2)
            {
                abort.Cancel();
            }
        }), abort.Token).WaitAsync(TimeSpan.FromSeconds(60), Token);
        var stop = Assert.IsType<RunStopPoint>(aborted.StopPoint);
        var reports = new List<RunProgress>();

        var resumed = await new ExecutorRunService().RunAsync(
            first with { Passes = 2, ResumeFrom = stop },
            new SynchronousProgress(p => { lock (reports) { reports.Add(p); } }),
            Token).WaitAsync(TimeSpan.FromSeconds(60), Token);

        Assert.Equal(RunOutcome.Aborted, aborted.Outcome);
        Assert.Equal(RunOutcome.Completed, resumed.Outcome);
        Assert.All(reports, p => Assert.Equal(1, p.Pass));
        Assert.True(stop.MoveIndex > 0);
        Assert.True(reports.Where(p => p.MovesDone > 0).Min(p => p.MovesDone) > stop.MoveIndex, "the resumed pass starts at the stop point, not at the first move");
        Assert.False((await TaskRunner.For(machine.TimeProvider).Run(() => machine.Gate.GetStateAsync(Token))).Firing);
    }

    private sealed class SynchronousProgress(Action<RunProgress> report) : IProgress<RunProgress>
    {
        public void Report(RunProgress value) => report(value);
    }
}
