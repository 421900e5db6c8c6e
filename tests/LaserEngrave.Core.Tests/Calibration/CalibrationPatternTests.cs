using LaserEngrave.Core.Calibration;
using LaserEngrave.Core.Geometry;

namespace LaserEngrave.Core.Tests.Calibration;

public class CalibrationPatternTests
{
    [Fact]
    public void Create_TwentyMmAtTenUm_TwoThousandPixelsWithTwoPixelLines()
    {
        var pattern = CalibrationPattern.Create(20, 10);

        Assert.Equal(2000, pattern.SidePx);
        Assert.Equal(2, pattern.LineWidthPx);

        // Marks a tenth of the size apart: 2 mm = 200 px.
        Assert.Equal(2.0, pattern.MarkSpacingMm, 12);
        Assert.Equal(200, pattern.MarkSpacingPx);
        Assert.Equal(12.0, pattern.SquareSideMm, 12);
    }

    [Fact]
    public void ToMask_Grooves_RunAlongXAndYThroughTheCrossing()
    {
        var pattern = CalibrationPattern.Create(20, 10);
        var mask = pattern.ToMask();
        var m = pattern.MarginPx;

        // The X groove's rows [m, m + 2) are burnt from m to side - m; the row above is burnt only at the marks.
        Assert.All(Enumerable.Range(m, pattern.SidePx - (2 * m)), x => Assert.True(mask[x, m] && mask[x, m + 1]));
        Assert.All(Enumerable.Range(m, pattern.SidePx - (2 * m)), y => Assert.True(mask[m, y] && mask[m + 1, y]));
        Assert.False(mask[m + 50, m - 1]);
        Assert.False(mask[m + 50, m + 2]);
    }

    [Fact]
    public void ToMask_ScaleMarks_CrossTheGroovesAtTheirNominalDistance()
    {
        var pattern = CalibrationPattern.Create(20, 10);
        var mask = pattern.ToMask();
        var m = pattern.MarginPx;
        for (var k = 1; k <= pattern.MarkCount; k++)
        {
            // Mark k's columns start k x 200 px right of the groove's left edge: its centre is k x 2 mm from the crossing's.
            var column = m + (k * 200);
            Assert.True(mask[column, m - 5], $"x mark {k}");
            Assert.False(mask[column - 1, m - 5], $"x mark {k} starts at its column");
            Assert.True(mask[m - 5, column], $"y mark {k}");
            Assert.Equal(2.0 * k, pattern.MarkDistanceMm(k), 12);
        }
    }

    [Fact]
    public void ToMask_Square_HasItsFourSidesAndTheMarkerInCornerA()
    {
        var pattern = CalibrationPattern.Create(20, 10);
        var mask = pattern.ToMask();

        // Corner centres in pixels: mm x 100; each side line covers the two pixels either side of its centre line.
        int ax = (int)Math.Round(pattern.SquareA.XMm * 100 - 1), ay = (int)Math.Round(pattern.SquareA.YMm * 100 - 1);
        var q = pattern.SquareSidePx;
        foreach (var (x, y) in new[] { (ax + (q / 2), ay), (ax + (q / 2), ay + q), (ax, ay + (q / 2)), (ax + q, ay + (q / 2)) })
        {
            Assert.True(mask[x, y] && mask[x + 1, y + 1], $"side through ({x}, {y})");
        }

        // The marker sits inside near A and nowhere near C.
        var nearA = Enumerable.Range(ax + 3, 80).Count(i => mask[i, i - ax + ay]);
        var nearC = Enumerable.Range(ax + q - 83, 80).Count(i => mask[i, i - ax + ay]);
        Assert.True(nearA > 30, $"marker near A: {nearA} px on the diagonal");
        Assert.Equal(0, nearC);
    }

    [Theory]
    [InlineData(0.5, 10.0)]
    [InlineData(20.0, 0.0)]
    [InlineData(-1.0, 10.0)]
    public void Create_UnusableSizeOrPitch_Throws(double sizeMm, double pitchUm)
    {
        Assert.Throws<CalibrationException>(() => CalibrationPattern.Create(sizeMm, pitchUm));
    }
}
