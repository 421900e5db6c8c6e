using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Jobs;
using LaserEngrave.Core.Planning;
using LaserEngrave.Core.Vectors;

namespace LaserEngrave.Core.Tests.Programs;

/// <summary>
/// The estimates added up over the programs are the figures `plan --json` gave before there were programs (main at
/// d97593d, `estimatedEngravingSeconds`): the samples in dot mode and as drawings. Since 2026-11-29 with the default
/// profile's gate processing of the reference firmware, 0.19 ms instead of 0.5 ms (docs/gate-firmware.md): each burst's
/// and switch-off's exchange 0.31 ms shorter (at d97593d: 71.04338790091549, 199.32531001133063, 303.8635250792571,
/// 283.1175420245126 s).
/// </summary>
public class ProgramEstimateTests
{
    private static string Asset(string name) => Logging.TestRuns.Asset(name);

    [Theory]
    // laserengrave plan assets/qr-code.bmp --width-mm 2 --mode dots --pulses-per-dot 3 --dot-settle-ms 2 --json
    [InlineData("qr-code.bmp", 2, 3, 2, 0, true, 563, 70.868547900915488)]
    // laserengrave plan assets/text-banner.png --width-mm 4 --mode dots --dot-pitch-microsteps 150 --unidirectional --json
    [InlineData("text-banner.png", 4, 1, 0, 150, false, 1956, 198.71864001133062)]
    public void DotEstimate_OverTheProgram_TheFiguresOfBefore(string image, double widthMm, int pulses, double settleMs, long pitch, bool bidirectional, long dots, double seconds)
    {
        var job = PreparedJob.Prepare(new JobSpec
        {
            ImagePath = Asset(image),
            Size = SizeSpec.Width(widthMm),
            Process = ProcessSettings.Default with { Mode = PlanMode.Dots, PulsesPerDot = pulses, DotSettleMs = settleMs, DotPitchMicrosteps = pitch },
            Plan = new PlanOptions { Bidirectional = bidirectional },
        });
        var program = ((DotJob)EngraveJob.Of(job)).Program();

        var estimate = DotModeEstimate.For(program);

        Assert.Equal(dots, estimate.Dots);
        Assert.Equal(seconds, estimate.TotalSeconds, 9);
        Assert.Equal(seconds, job.Statistics.EngravingSeconds, 9);
        Assert.Equal(estimate.TotalSeconds - program.Timing.OffRoundTripSeconds, program.SecondsBefore(dots), 9);
    }

    [Theory]
    // laserengrave plan assets/drawings/hexagons.dxf --origin-mm 5,5 --json
    [InlineData("hexagons.dxf", null, 5, 39, 303.86321507925709)]
    // laserengrave plan assets/drawings/every-command.svg --width-mm 40 --origin-mm 2,2 --json; 37 strokes since corners the
    // axes cannot follow are split before the first build (issue 38): the old whole-path build also split a gentle vertex
    // after a sharp corner, for the corner's after-effect alone (38 strokes, 283.117 s).
    [InlineData("every-command.svg", 40.0, 2, 37, 282.91018163399355)]
    public void DrawingEstimate_OverTheProgram_TheFiguresOfBefore(string drawing, double? widthMm, double originMm, int strokes, double seconds)
    {
        var spec = new JobSpec
        {
            ImagePath = Asset(Path.Combine("drawings", drawing)),
            Size = SizeSpec.Width(widthMm ?? 1),
            Origin = new OriginMm(originMm, originMm),
        };
        var prepared = widthMm is null ? PreparedDrawing.PrepareOwnSize(spec, VectorOptions.Default) : PreparedDrawing.Prepare(spec, VectorOptions.Default);
        var program = ((DrawingJob)EngraveJob.Of(prepared)).Program();

        Assert.Equal(strokes, program.StrokeCount);
        Assert.Equal(seconds, program.SecondsFrom(0), 9);
        Assert.Equal(seconds, prepared.Schedule.EstimatedSeconds, 9);
    }
}
