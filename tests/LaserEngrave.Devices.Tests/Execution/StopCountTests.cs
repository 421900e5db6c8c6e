using LaserEngrave.Core.Jobs;
using LaserEngrave.Core.Planning;
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
}
