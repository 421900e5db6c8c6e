using LaserEngrave.Core.Jobs;
using LaserEngrave.Core.Planning;
using LaserEngrave.Devices.Execution;

namespace LaserEngrave.Devices.Tests.Execution;

/// <summary>Whole runs on the in-process simulator in virtual time: the burned image, the laser, progress and the result.</summary>
public class RunExecutorTests
{
    [Theory(Timeout = 120_000)]
    [InlineData(PlanStrategy.Paper, false, 0.0)]
    [InlineData(PlanStrategy.Optimized, false, 0.0)]
    [InlineData(PlanStrategy.Optimized, true, 0.0)]
    [InlineData(PlanStrategy.Optimized, true, 0.05)]
    [InlineData(PlanStrategy.Optimized, false, 0.05)]
    public async Task RunAsync_RandomMask_BurnsExactlyTheMask(PlanStrategy strategy, bool bidirectional, double overscanMm)
    {
        await using var run = SimulatedRun.Create();
        var job = TestJobs.FromMask(TestJobs.RandomMask(seed: 7, 24, 12), 1.2, new PlanOptions { Strategy = strategy, Bidirectional = bidirectional, OverscanMm = overscanMm });

        var result = await run.Do(() => run.Executor(job).RunAsync(TestContext.Current.CancellationToken));
        var report = run.Analyze(job);

        Assert.True(result.Outcome == RunOutcome.Completed, $"{result.Outcome}: {result.FaultMessage}");
        Assert.True(report.Burned.ContentEquals(job.Mask), $"burned differs: {report.ExtraPixels} extra, {report.MissingPixels} missing");
        Assert.Equal(0, report.LaserOnTravelCount);
        Assert.Equal(0, report.DwellCount);
        Assert.False(run.Machine.Gate.IsFiring);
        Assert.Equal(job.Statistics.BurnRuns, result.RunsDone);
        Assert.Equal(job.Statistics.Rows, result.RowsDone);
    }

    [Theory(Timeout = 300_000)]
    [InlineData(PlanStrategy.Paper, false, 0.0)]
    [InlineData(PlanStrategy.Optimized, false, 0.0)]
    [InlineData(PlanStrategy.Optimized, true, 0.0)]
    [InlineData(PlanStrategy.Optimized, true, 0.1)]
    [InlineData(PlanStrategy.Optimized, false, 0.1)]
    public async Task RunAsync_QrSampleFiveMillimetres_BurnsExactlyTheMask(PlanStrategy strategy, bool bidirectional, double overscanMm)
    {
        await using var run = SimulatedRun.Create();
        var job = TestJobs.FromAsset("qr-code.bmp", 5, new PlanOptions { Strategy = strategy, Bidirectional = bidirectional, OverscanMm = overscanMm });

        var result = await run.Do(() => run.Executor(job).RunAsync(TestContext.Current.CancellationToken));
        var report = run.Analyze(job);

        Assert.True(result.Outcome == RunOutcome.Completed, $"{result.Outcome}: {result.FaultMessage}");
        Assert.True(report.Burned.ContentEquals(job.Mask), $"burned differs: {report.ExtraPixels} extra, {report.MissingPixels} missing");
        Assert.Equal(0, report.LaserOnTravelCount);
        Assert.Equal(0, report.DwellCount);
        Assert.Equal(0, report.RefusedMoves);
    }
}
