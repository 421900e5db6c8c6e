using LaserEngrave.Core.Geometry;

namespace LaserEngrave.Core.Tests.Geometry;

/// <summary>Focus positions: absolute Z microsteps from the visible focus, rounded once, and the limits they must keep.</summary>
public class ZAxisProfileTests
{
    private static readonly ZAxisProfile Z = new() { FocusMm = 12.5, MinMm = 5, MaxMm = 20 };

    [Theory]
    [InlineData(0, 125984)] // 12500 µm / 0.09921875 = 125984.25
    [InlineData(-200, 123969)] // 12300 / 0.09921875 = 123968.50
    [InlineData(200, 128000)] // 12700 / 0.09921875 = 128000.00
    public void MicrostepsAt_Offset_AbsolutePositionFromTheVisibleFocus(double offsetUm, long expected)
    {
        Assert.Equal(expected, Z.MicrostepsAt(offsetUm));
    }

    [Fact]
    public void MicrostepsAt_SmallOffset_RoundedOnceFromTheAbsolutePosition()
    {
        // 12500.04 µm = 125984.65 microsteps -> 125985; rounding the focus (125984) and the offset (0.40 -> 0) apart would give 125984.
        Assert.Equal(125985, Z.MicrostepsAt(0.04));
        Assert.Equal((long)Math.Round(StageUnits.UmToMicrosteps(12500.04, Z.MicrostepUm)), Z.MicrostepsAt(0.04));
    }

    [Theory]
    [InlineData(-7500, null)] // 5 mm: the lower limit itself
    [InlineData(7500, null)] // 20 mm: the upper limit itself
    [InlineData(-7600, "puts Z at 4.9 mm, outside z.minMm..z.maxMm 5..20 mm")]
    [InlineData(7600, "puts Z at 20.1 mm, outside z.minMm..z.maxMm 5..20 mm")]
    [InlineData(double.NaN, "outside z.minMm..z.maxMm")]
    public void OffsetProblem_OutsideTheLimits_SaysWhere(double offsetUm, string? expected)
    {
        var problem = Z.OffsetProblem(offsetUm);

        if (expected is null)
        {
            Assert.Null(problem);
        }
        else
        {
            Assert.Contains(expected, problem, StringComparison.Ordinal);
        }
    }

    [Fact]
    public void UpperMm_NoMaxMm_TheTravel()
    {
        Assert.Equal(25, new ZAxisProfile().UpperMm);
    }
}
