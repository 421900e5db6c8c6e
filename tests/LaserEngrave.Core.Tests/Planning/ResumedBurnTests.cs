using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Jobs;
using LaserEngrave.Core.Planning;

namespace LaserEngrave.Core.Tests.Planning;

public class ResumedBurnTests
{
    private static PreparedJob Qr(PlanMode mode = PlanMode.Raster) => PreparedJob.Prepare(new JobSpec
    {
        ImagePath = Logging.TestRuns.Asset("qr-code.bmp"),
        Size = SizeSpec.Width(3),
        Process = ProcessSettings.Default with { Mode = mode },
    });

    [Theory]
    [InlineData(PlanMode.Raster)]
    [InlineData(PlanMode.Dots)]
    public void BurnedBefore_StopAtStartOrEnd_NothingOrTheWholeMask(PlanMode mode)
    {
        var job = Qr(mode);
        var moves = mode == PlanMode.Dots ? job.Dots!.Dots().LongCount() : job.Plan.Moves().LongCount();

        Assert.Equal(0, ResumedBurn.BurnedBefore(job, new RunStopPoint(0, 0)).CountSet());
        Assert.True(ResumedBurn.BurnedBefore(job, new RunStopPoint(job.Mask.Height, moves)).ContentEquals(job.Mask));
        Assert.True(ResumedBurn.StillToBurn(job, new RunStopPoint(0, 0)).ContentEquals(job.Mask));
    }

    [Fact]
    public void StillToBurn_StopInsideABurn_TheRunsBeforeAreNotExpectedAndTheCutPixelIs()
    {
        var job = Qr();
        var moves = job.Plan.Moves().ToList();
        var index = moves.FindIndex(m => m.Kind == MoveKind.Burn && Math.Abs(m.X1 - m.X0) > 2 * job.Plan.Geometry.PitchMicrosteps && m.Row > 5);
        var burn = moves[index];
        var middle = (burn.X0 + burn.X1) / 2;
        var cut = job.Plan.ColumnAt(burn, middle);

        var before = ResumedBurn.BurnedBefore(job, new RunStopPoint(burn.Row, index) { ResumeXMicrosteps = middle });
        var still = ResumedBurn.StillToBurn(job, new RunStopPoint(burn.Row, index) { ResumeXMicrosteps = middle });

        // Every black pixel is either burned before or still to burn, never both; the pixel the stop cut through is burned again.
        Assert.Equal(job.Mask.CountSet(), before.CountSet() + still.CountSet());
        Assert.False(before[cut, burn.Row]);
        Assert.True(still[cut, burn.Row]);
        Assert.True(before[job.Plan.ColumnAt(burn, burn.X0 + (burn.X1 > burn.X0 ? 1 : -1)), burn.Row]);
        Assert.True(still[job.Plan.ColumnAt(burn, burn.X1 + (burn.X1 > burn.X0 ? -1 : 1)), burn.Row]);
    }
}
