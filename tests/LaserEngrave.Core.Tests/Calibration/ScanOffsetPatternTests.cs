using LaserEngrave.Core.Calibration;
using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Planning;

namespace LaserEngrave.Core.Tests.Calibration;

public class ScanOffsetPatternTests
{
    [Fact]
    public void Create_Sizes_RoundedToWholePixels()
    {
        var pattern = ScanOffsetPattern.Create(25, 200, 510, 5, 300);

        Assert.Equal(8, pattern.BarWidthPx);
        Assert.Equal(12, pattern.GapPx);
        Assert.Equal(20, pattern.BarHeightPx);
        Assert.Equal((5 * 8) + (4 * 12), pattern.WidthPx);
    }

    [Theory]
    [InlineData(475, 20)] // 19 rows -> 20
    [InlineData(500, 20)]
    [InlineData(30, 2)] // one row -> two, one each way
    public void Create_BarHeight_RoundedUpToAnEvenNumberOfRows(double heightUm, int rows)
    {
        Assert.Equal(rows, ScanOffsetPattern.Create(25, 200, heightUm, 5, 300).BarHeightPx);
    }

    [Fact]
    public void ToMask_Bars_AreFilledAndTheGapsEmpty()
    {
        var pattern = ScanOffsetPattern.Create(10, 30, 40, 3, 20);
        var mask = pattern.ToMask();

        // Bars at columns 0..2, 5..7, 10..12, every row.
        Assert.Equal(13, mask.Width);
        Assert.Equal(4, mask.Height);
        for (var column = 0; column < mask.Width; column++)
        {
            var inBar = column % 5 < 3;
            for (var row = 0; row < mask.Height; row++)
            {
                Assert.Equal(inBar, mask[column, row]);
            }
        }
    }

    [Fact]
    public void Plan_Bidirectional_EveryBarHalfLeftToRightHalfRightToLeft()
    {
        var pattern = ScanOffsetPattern.Create(25, 200, 500, 5, 300);
        var mask = pattern.ToMask();
        var geometry = GeometryResolver.Resolve(SizeSpec.Pitch(25), mask.Width, mask.Height, new OriginMm(10, 10), MachineProfile.Default).Geometry;
        var burns = new RasterPlan(mask, geometry).Moves().Where(m => m.Kind == MoveKind.Burn).ToList();

        Assert.Equal(5 * 20, burns.Count);
        Assert.Equal(50, burns.Count(m => m.X1 > m.X0));
        Assert.All(burns, m => Assert.Equal(m.Row % 2 == 0, m.X1 > m.X0));
    }

    [Theory]
    [InlineData(0, 200, 500, 5, 300, "pitch 0 µm must be a finite number above 0")]
    [InlineData(25, 10, 500, 5, 300, "bar width 10 µm is less than one pixel of 25 µm")]
    [InlineData(25, 200, double.NaN, 5, 300, "bar height NaN µm must be a finite number above 0")]
    [InlineData(25, 200, 500, 0, 300, "0 bars: give 1..100")]
    [InlineData(25, 200, 500, 101, 300, "101 bars: give 1..100")]
    [InlineData(0.1, 2000, 500, 100, 2000, "a pattern of 100 bars is 3980000 x 5000 pixels")]
    public void Create_BadValue_OneLineNamingIt(double pitch, double width, double height, int bars, double gap, string expected)
    {
        var ex = Assert.Throws<CalibrationException>(() => ScanOffsetPattern.Create(pitch, width, height, bars, gap));

        Assert.Contains(expected, ex.Message, StringComparison.Ordinal);
    }
}
