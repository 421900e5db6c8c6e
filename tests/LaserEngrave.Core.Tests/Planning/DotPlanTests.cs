using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Imaging;
using LaserEngrave.Core.Planning;

namespace LaserEngrave.Core.Tests.Planning;

/// <summary>Where dot mode stops, computed by hand: pixel centres, or k microsteps apart centred on each run; serpentine rows.</summary>
public class DotPlanTests
{
    // 1000 microsteps a pixel of 0.1 µm, origin 0: pixel c spans [1000 c, 1000 (c + 1)), row r burns along y = 1000 r + 500.
    private static readonly JobGeometry Geometry = new(4, 3, 1000, 0, 0, 0.1, 1_000_000, 1_000_000);

    private static BitMask Mask(params string[] rows)
    {
        var mask = new BitMask(rows[0].Length, rows.Length);
        for (var y = 0; y < rows.Length; y++)
        {
            for (var x = 0; x < rows[y].Length; x++)
            {
                mask[x, y] = rows[y][x] == '#';
            }
        }

        return mask;
    }

    private static DotPlan Plan(long pitch = 0, bool bidirectional = true, JobGeometry? geometry = null) => new(
        Mask("##.#", "....", ".##."),
        geometry ?? Geometry,
        ProcessSettings.Default with { Mode = PlanMode.Dots, PulsesPerDot = 3, DotPitchMicrosteps = pitch },
        MachineProfile.Default,
        new PlanOptions { Bidirectional = bidirectional });

    [Fact]
    public void Dots_EveryPixel_PixelCentresSerpentine()
    {
        var dots = Plan().Dots().ToList();

        Assert.Equal(
            [new Dot(500, 500, 0), new Dot(1500, 500, 0), new Dot(3500, 500, 0), new Dot(2500, 2500, 2), new Dot(1500, 2500, 2)],
            dots);
    }

    [Fact]
    public void Dots_Unidirectional_EveryRowLeftToRight()
    {
        var dots = Plan(bidirectional: false).Dots().Where(d => d.Row == 2).Select(d => d.X);

        Assert.Equal([1500L, 2500L], dots);
    }

    [Fact]
    public void Dots_PitchThreeHundred_CentredOnEachRun()
    {
        var dots = Plan(pitch: 300).Dots().ToList();

        // [0, 2): 2000 long, 6 dots 300 apart need 1500, so the first is 250 in; [3, 4): 3 dots, 200 in; row 2 [1, 3) backwards.
        Assert.Equal([250L, 550, 850, 1150, 1450, 1750, 3200, 3500, 3800], dots.Where(d => d.Row == 0).Select(d => d.X));
        Assert.Equal([2750L, 2450, 2150, 1850, 1550, 1250], dots.Where(d => d.Row == 2).Select(d => d.X));
        Assert.Equal(15, Plan(pitch: 300).Estimate.Dots);
    }

    [Fact]
    public void Dots_PitchLongerThanTheRun_OneDotAtItsCentre()
    {
        var dots = Plan(pitch: 1500).Dots().Where(d => d.Row == 0).Select(d => d.X);

        // [0, 2): one dot (2000 / 1500 = 1.33), at 1000; [3, 4): one at 3500.
        Assert.Equal([1000L, 3500L], dots);
    }

    [Fact]
    public void Dots_FromAnIndex_TheSameDotsFromThere()
    {
        var plan = Plan(pitch: 300);

        Assert.Equal(plan.Dots().Skip(7), plan.Dots(7));
        Assert.Empty(plan.Dots(15));
    }

    [Fact]
    public void Dots_UnroundedPitchAndOrigin_EachPositionRoundedOnce()
    {
        // Pitch 1000.4 and origin 0.3: pixel 3's centre is 0.3 + 3.5 x 1000.4 = 3501.7, rounded once to 3502, on y = 0.3 + 0.5 x 1000.4 = 500.5, 501.
        var geometry = new JobGeometry(4, 3, 1000.4, 0.3, 0.3, 0.1, 1_000_000, 1_000_000);

        var dots = Plan(geometry: geometry).Dots().ToList();

        Assert.Equal(new Dot(3502, 501, 0), dots[2]);
        Assert.Equal(new Dot(2501, 2501, 2), dots[3]);
    }

    [Fact]
    public void Estimate_DefaultProcess_AddsUpTheModelByHand()
    {
        var plan = Plan();
        var t = plan.Timing;

        // At 9600 baud a byte is 1.0417 ms: a Zaber frame 6.25 ms; "BURST 3 1000\n" 13 bytes, "OK BURST 3\n" 11 bytes.
        Assert.Equal(0.00625, t.FrameSeconds, 12);
        Assert.Equal("BURST 3 1000\n", t.BurstCommand);
        // The default profile's gate processing: 0.19 ms, the reference firmware's for a BURST line (docs/gate-firmware.md).
        const double Processing = 0.00019;
        Assert.Equal(0.001 + (13 * 10 / 9600.0) + Processing, t.BurstLeadSeconds, 12);
        Assert.Equal((11 * 10 / 9600.0) + 0.001, t.BurstReplySeconds, 12);

        // The burst (3 ms) is over before its 11.46 ms reply has even crossed the wire: only the reaction margin is left to wait.
        Assert.Equal(0.0005, t.AfterAckSeconds, 12);

        // 5 dots, 4 steps: 1000 and 2000 microsteps along X, then a row change of (-1000, +2000), then 1000 along X.
        // Travel 4 mm/s = 40 323 microsteps/s quantised to 4301 x 9.375; 50 mm/s² = 44 x 11 250 microsteps/s².
        var v = 4301 * 9.375;
        var a = 44 * 11250.0;
        double Move(double d) => d < v * v / a ? 2 * Math.Sqrt(d / a) : (v / a) + (d / v);
        var stage = 0.001 + 0.00625;
        var steps = (stage + Move(1000) + 0.00625 + 0.001)
            + (stage + Move(2000) + 0.00625 + 0.001)
            + (0.001 + Math.Max(0.00625 + Move(1000), 0.0125 + Move(2000)) + 0.00625 + 0.001)
            + (stage + Move(1000) + 0.00625 + 0.001);
        Assert.Equal(steps, plan.Estimate.StepsSeconds, 9);
        var atDot = t.BurstLeadSeconds + t.BurstReplySeconds + 0.0005;
        Assert.Equal(atDot, plan.Estimate.AtDotSeconds, 12);
        var off = 0.002 + Processing + ((4 + 10) * 10 / 9600.0);
        Assert.Equal((4 * 2 * stage) + off + steps + (5 * atDot), plan.Estimate.TotalSeconds, 9);
        Assert.Equal(15, plan.Estimate.Pulses);
        Assert.Equal(2, plan.Estimate.Rows);
    }

    [Fact]
    public void Estimate_LongBurst_WaitsForItsEndAfterTheAcknowledgement()
    {
        var plan = new DotPlan(
            Mask("#"),
            new JobGeometry(1, 1, 1000, 0, 0, 0.1, 1_000_000, 1_000_000),
            ProcessSettings.Default with { Mode = PlanMode.Dots, PulsesPerDot = 100, LaserFrequencyHz = 1000 },
            MachineProfile.Default);

        // 100 ms of burst, less the reply "OK BURST 100\n" (13 bytes) and the adapter's least latency (0.5 ms), plus 0.5 ms.
        Assert.Equal(0.1 - (13 * 10 / 9600.0) - 0.0005 + 0.0005, plan.Timing.AfterAckSeconds, 12);
        Assert.Null(plan.Problem);
    }

    [Fact]
    public void Problem_BurstLongerThanHalfTheWatchdog_RefusedWithOneLine()
    {
        var plan = new DotPlan(
            Mask("#"),
            new JobGeometry(1, 1, 1000, 0, 0, 0.1, 1_000_000, 1_000_000),
            ProcessSettings.Default with { Mode = PlanMode.Dots, PulsesPerDot = 600, LaserFrequencyHz = 1000 },
            MachineProfile.Default);

        Assert.Contains("600 pulses at 1000 Hz lasts 600 ms", plan.Problem);
        Assert.Contains(plan.Warnings, w => w.Kind == JobWarningKind.BurstTooLongForTheWatchdog);
    }
}
