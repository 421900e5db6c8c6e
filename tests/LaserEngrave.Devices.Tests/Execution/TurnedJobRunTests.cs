using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Imaging;
using LaserEngrave.Core.Jobs;
using LaserEngrave.Core.Planning;

namespace LaserEngrave.Devices.Tests.Execution;

/// <summary>A turned and mirrored job on the twin: what burns is the image as turned on the stage, not as the file stands.</summary>
public class TurnedJobRunTests
{
    [Theory(Timeout = 300_000)]
    [InlineData(1, false, false)]
    [InlineData(3, true, false)]
    [InlineData(0, false, true)]
    public async Task RunAsync_TextBannerTurnedOrMirrored_BurnsTheTurnedMask(int turns, bool mirrorX, bool mirrorY)
    {
        await using var run = SimulatedRun.Create();
        var options = new MaskOptions { QuarterTurns = turns, MirrorX = mirrorX, MirrorY = mirrorY };
        var job = PreparedJob.Prepare(new JobSpec
        {
            ImagePath = TestJobs.AssetPath("text-banner.png"),
            Mask = options,
            Size = SizeSpec.Pitch(20),
            Origin = TestJobs.Origin,
            Plan = new PlanOptions { Strategy = PlanStrategy.Optimized, Bidirectional = true },
        });
        var upright = MaskBuilder.FromFile(TestJobs.AssetPath("text-banner.png"), MaskOptions.Default, out _);

        var result = await run.Do(() => run.Executor(job).RunAsync(TestContext.Current.CancellationToken));
        var report = run.Analyze(job);

        // The plan's mask is the file's turned pixel by pixel, (x, y) of the file to where the stage shows it.
        Assert.Equal(turns % 2 == 1 ? (upright.Height, upright.Width) : (upright.Width, upright.Height), (job.Mask.Width, job.Mask.Height));
        for (var y = 0; y < upright.Height; y++)
        {
            for (var x = 0; x < upright.Width; x++)
            {
                var mx = mirrorX ? upright.Width - 1 - x : x;
                var my = mirrorY ? upright.Height - 1 - y : y;
                var (tx, ty) = turns switch
                {
                    1 => (upright.Height - 1 - my, mx),
                    2 => (upright.Width - 1 - mx, upright.Height - 1 - my),
                    3 => (my, upright.Width - 1 - mx),
                    _ => (mx, my),
                };
                if (upright[x, y] != job.Mask[tx, ty])
                {
                    Assert.Fail($"file pixel ({x}, {y}) is not at ({tx}, {ty}) of the turned mask");
                }
            }
        }

        Assert.True(result.Outcome == RunOutcome.Completed, $"{result.Outcome}: {result.FaultMessage}");
        Assert.True(report.Burned.ContentEquals(job.Mask), $"burned differs: {report.ExtraPixels} extra, {report.MissingPixels} missing");
        Assert.Equal(0, report.LaserOnTravelCount);
    }
}
