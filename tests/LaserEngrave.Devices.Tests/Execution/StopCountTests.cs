using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Jobs;
using LaserEngrave.Core.Logging;
using LaserEngrave.Core.Planning;
using LaserEngrave.Core.Vectors;
using LaserEngrave.Devices.Execution;

namespace LaserEngrave.Devices.Tests.Execution;

/// <summary>Issue 23: after an abort, the run's last progress, its result (the log's count) and the continued run's first progress count the same rows and runs done.</summary>
public sealed class StopCountTests(ITestOutputHelper output)
{
    [Theory(Timeout = 120_000)]
    [InlineData(PlanMode.Raster, PlanStrategy.Optimized, 20)]
    [InlineData(PlanMode.Raster, PlanStrategy.Optimized, 41)]
    [InlineData(PlanMode.Raster, PlanStrategy.Paper, 20)]
    [InlineData(PlanMode.Dots, PlanStrategy.Optimized, 20)]
    public async Task Abort_ThenContinue_RowsAndRunsDoneAgree(PlanMode mode, PlanStrategy strategy, double abortAfterSeconds)
    {
        var job = TestJobs.FromAsset("qr-code.bmp", 3, new PlanOptions { Strategy = strategy }, ProcessSettings.Default with { Mode = mode });
        RunProgress? last = null;
        RunResult stopped;
        await using (var run = SimulatedRun.Create())
        {
            var executor = run.Executor(job);
            var asked = 0;
            executor.ProgressChanged += (_, p) =>
            {
                last = p;
                if (p.State == RunState.Running && Interlocked.Exchange(ref asked, 1) == 0)
                {
                    _ = Task.Delay(TimeSpan.FromSeconds(abortAfterSeconds), run.Time).ContinueWith(_ => executor.Abort(), run.Loop);
                }
            };
            stopped = await run.Do(() => executor.RunAsync(TestContext.Current.CancellationToken));
        }

        RunProgress? first = null;
        await using (var again = SimulatedRun.Create())
        {
            var resumed = again.Executor(job, new RunOptions { ResumeFrom = stopped.StopPoint });
            resumed.ProgressChanged += (_, p) => first ??= p.State == RunState.Running ? p : null;
            await again.Do(() => resumed.RunAsync(TestContext.Current.CancellationToken));
        }

        output.WriteLine($"stopped: {last!.Percent:0.#} %, rows {last.RowsDone}, runs {last.RunsDone}; result rows {stopped.RowsDone}, runs {stopped.RunsDone}, stop row {stopped.StopPoint!.Row} move {stopped.StopPoint.MoveIndex}; continued: {first!.Percent:0.#} %, rows {first.RowsDone}, runs {first.RunsDone}");
        Assert.Equal(RunOutcome.Aborted, stopped.Outcome);
        Assert.Equal((stopped.RowsDone, stopped.RunsDone), (last.RowsDone, last.RunsDone));
        Assert.Equal((stopped.RowsDone, stopped.RunsDone), (first.RowsDone, first.RunsDone));
    }

    [Fact(Timeout = 120_000)]
    public async Task RunAsync_DrawingWithAPathTooShortToBurn_ProgressResultAndLogCountThePathsBurned()
    {
        // The 3 µm line is too short to switch the laser on and off: it is not burned, so it is no path left to do.
        var path = TestDrawing.Svg("<line x1=\"1\" y1=\"1\" x2=\"1.003\" y2=\"1\"/><line x1=\"2\" y1=\"2\" x2=\"4\" y2=\"2\"/><line x1=\"2\" y1=\"4\" x2=\"4\" y2=\"4\"/>");
        var drawing = PreparedDrawing.PrepareOwnSize(new JobSpec { ImagePath = path, Size = SizeSpec.Width(1), Origin = new OriginMm(5, 5) }, VectorOptions.Default);
        var logged = RunRecord.ForDrawing(drawing, new string('0', 64), DateTimeOffset.UnixEpoch);
        RunProgress? idle = null, last = null;
        RunResult result;
        await using (var run = SimulatedRun.Create())
        {
            var executor = new RunExecutor(run.Stage, run.Gate, drawing, run.Time);
            idle = executor.Progress;
            executor.ProgressChanged += (_, p) => last = p;
            result = await run.Do(() => executor.RunAsync(TestContext.Current.CancellationToken));
        }

        output.WriteLine($"paths {drawing.Plan.Paths.Count}, burned {drawing.PathsBurned}; idle {idle.RunsTotal}, last {last!.RunsDone} of {last.RunsTotal}, result {result.RunsDone} of {result.RunsTotal}, log {logged.RunsTotal}");
        Assert.Equal(3, drawing.Plan.Paths.Count);
        Assert.Equal(RunOutcome.Completed, result.Outcome);
        Assert.Equal(logged.RunsTotal, idle.RunsTotal);
        Assert.Equal((logged.RunsTotal, logged.RunsTotal), (last.RunsDone, last.RunsTotal));
        Assert.Equal((logged.RunsTotal, logged.RunsTotal), (result.RunsDone, result.RunsTotal));
        Assert.Equal(drawing.PathsBurned, logged.RunsTotal);
    }

    [Fact(Timeout = 120_000)]
    public async Task Abort_DrawingWithAPathTooShortToBurn_ContinuedRunEndsWithEveryPathBurnedCounted()
    {
        var path = TestDrawing.Svg("<line x1=\"1\" y1=\"1\" x2=\"1.003\" y2=\"1\"/><line x1=\"2\" y1=\"2\" x2=\"4\" y2=\"2\"/><line x1=\"2\" y1=\"4\" x2=\"4\" y2=\"4\"/><line x1=\"2\" y1=\"6\" x2=\"4\" y2=\"6\"/>");
        var drawing = PreparedDrawing.PrepareOwnSize(new JobSpec { ImagePath = path, Size = SizeSpec.Width(1), Origin = new OriginMm(5, 5) }, VectorOptions.Default);
        RunProgress? last = null;
        RunResult stopped;
        await using (var run = SimulatedRun.Create())
        {
            var executor = new RunExecutor(run.Stage, run.Gate, drawing, run.Time);
            var asked = 0;
            executor.ProgressChanged += (_, p) =>
            {
                last = p;
                if (p.RunsDone == 1 && Interlocked.Exchange(ref asked, 1) == 0)
                {
                    _ = Task.Delay(TimeSpan.FromMilliseconds(100), run.Time).ContinueWith(_ => executor.Abort(), run.Loop);
                }
            };
            stopped = await run.Do(() => executor.RunAsync(TestContext.Current.CancellationToken));
        }

        RunProgress? first = null, end = null;
        RunResult continued;
        await using (var again = SimulatedRun.Create())
        {
            var resumed = new RunExecutor(again.Stage, again.Gate, drawing, again.Time, new RunOptions { ResumeFrom = stopped.StopPoint });
            resumed.ProgressChanged += (_, p) =>
            {
                first ??= p.State == RunState.Running ? p : null;
                end = p;
            };
            continued = await again.Do(() => resumed.RunAsync(TestContext.Current.CancellationToken));
        }

        output.WriteLine($"stopped: runs {last!.RunsDone} of {last.RunsTotal}, result {stopped.RunsDone} of {stopped.RunsTotal}, stop stroke {stopped.StopPoint!.Row}; continued: first {first!.RunsDone}, end {end!.RunsDone} of {end.RunsTotal}");
        Assert.Equal(RunOutcome.Aborted, stopped.Outcome);
        Assert.InRange(stopped.RunsDone, 1, drawing.PathsBurned - 1);
        Assert.Equal((stopped.RunsDone, stopped.RunsTotal), (last.RunsDone, last.RunsTotal));
        Assert.Equal(stopped.RunsDone, first.RunsDone);
        Assert.Equal(RunOutcome.Completed, continued.Outcome);
        Assert.Equal((3L, 3L), (end.RunsDone, end.RunsTotal));
        Assert.Equal((3L, 3L), (continued.RunsDone, continued.RunsTotal));
    }
}
