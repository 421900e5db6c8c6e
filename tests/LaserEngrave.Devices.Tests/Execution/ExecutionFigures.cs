using System.Globalization;
using LaserEngrave.Core.Jobs;
using LaserEngrave.Core.Planning;
using LaserEngrave.Devices.Execution;

namespace LaserEngrave.Devices.Tests.Execution;

/// <summary>
/// The report's figures, measured on the in-process simulator in virtual time: paper against optimized on the QR sample,
/// and the estimate against the simulated time for the three samples. Run with
/// <c>dotnet test tests/LaserEngrave.Devices.Tests --filter Category=Figures --logger "console;verbosity=detailed"</c>;
/// the table is also written to execution-figures.md in the test output folder.
/// </summary>
[Trait("Category", "Figures")]
public class ExecutionFigures
{
    private const double WidthMm = 5;

    [Fact(Timeout = 900_000)]
    public async Task Samples_EstimateAndSimulatedTime_AgreeWithinFivePercent_OptimizedThreeTimesFasterOnQr()
    {
        var lines = new List<string>
        {
            $"| sample ({WidthMm} mm wide) | strategy | moves | burn runs | estimated s | simulated s (engraving) | difference | whole run s (with preflight, homing, positioning) | burned == mask |",
            "|---|---|---|---|---|---|---|---|---|",
        };
        var simulated = new Dictionary<(string, PlanStrategy), double>();
        var worst = 0.0;
        foreach (var (sample, strategy) in new[]
                 {
                     ("qr-code.bmp", PlanStrategy.Paper), ("qr-code.bmp", PlanStrategy.Optimized),
                     ("text-banner.png", PlanStrategy.Optimized), ("line-drawing.png", PlanStrategy.Optimized),
                 })
        {
            var job = TestJobs.FromAsset(sample, WidthMm, new PlanOptions { Strategy = strategy });
            await using var run = SimulatedRun.Create();
            var result = await run.Do(() => run.Executor(job).RunAsync(TestContext.Current.CancellationToken));
            var report = run.Analyze(job);
            var seconds = result.EngravingDuration.TotalSeconds;
            var difference = (result.EstimatedEngravingSeconds / seconds) - 1;
            worst = Math.Max(worst, Math.Abs(difference));
            simulated[(sample, strategy)] = seconds;
            lines.Add(string.Create(
                CultureInfo.InvariantCulture,
                $"| {sample} | {strategy} | {job.Statistics.Moves} | {job.Statistics.BurnRuns} | {result.EstimatedEngravingSeconds:0.0} | {seconds:0.0} | {Percent(difference)} | {result.Duration.TotalSeconds:0.0} | {report.Burned.ContentEquals(job.Mask)} |"));
            Assert.True(result.Outcome == RunOutcome.Completed, $"{result.Outcome}: {result.FaultMessage}");
            Assert.True(report.Burned.ContentEquals(job.Mask), $"{sample} {strategy}: burned differs from the mask");
            Assert.Equal(0, report.LaserOnTravelCount);
            Assert.True(report.DwellCount == 0, $"{sample} {strategy}: {report.DwellCount} dwell(s), the longest {report.LongestDwellSeconds * 1000:0.0} ms");
        }

        var speedup = simulated[("qr-code.bmp", PlanStrategy.Paper)] / simulated[("qr-code.bmp", PlanStrategy.Optimized)];
        lines.Add(string.Empty);
        lines.Add(string.Create(CultureInfo.InvariantCulture, $"qr-code.bmp at {WidthMm} mm: optimized is {speedup:0.00}x faster than paper (simulated time); worst estimate difference {worst:0.00%}."));
        var text = string.Join('\n', lines);
        TestContext.Current.TestOutputHelper?.WriteLine(text);
        await File.WriteAllTextAsync(Path.Combine(AppContext.BaseDirectory, "execution-figures.md"), text + "\n", TestContext.Current.CancellationToken);

        Assert.True(speedup >= 3, $"optimized is only {speedup:0.00}x faster than paper");
        Assert.True(worst <= 0.05, $"the estimate is {worst:0.00%} off the simulated time");
    }

    private static string Percent(double fraction)
    {
        var rounded = Math.Round(fraction * 100, 2) + 0.0;
        return string.Create(CultureInfo.InvariantCulture, $"{(rounded > 0 ? "+" : string.Empty)}{rounded:0.00} %");
    }
}
