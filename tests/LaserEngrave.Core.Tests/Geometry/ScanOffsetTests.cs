using LaserEngrave.Core.Geometry;

namespace LaserEngrave.Core.Tests.Geometry;

public class ScanOffsetTests
{
    private static readonly ScanOffset[] Table = [new(0.5, 2), new(1, 4), new(4, 10)];

    [Theory]
    [InlineData(0.5, 2)]
    [InlineData(1, 4)]
    [InlineData(4, 10)]
    public void At_ATableSpeed_IsItsOffset(double speed, double offset)
    {
        Assert.Equal(offset, ScanOffset.At(Table, speed), 12);
    }

    [Theory]
    [InlineData(0.75, 3)]
    [InlineData(2.5, 7)]
    [InlineData(3.7, 9.4)]
    public void At_BetweenTwoSpeeds_IsLinear(double speed, double offset)
    {
        Assert.Equal(offset, ScanOffset.At(Table, speed), 12);
    }

    [Theory]
    [InlineData(0.1, 2)]
    [InlineData(0.001, 2)]
    [InlineData(5, 10)]
    [InlineData(30, 10)]
    public void At_BeyondTheEnds_IsTheEndsOffset(double speed, double offset)
    {
        Assert.Equal(offset, ScanOffset.At(Table, speed), 12);
    }

    [Fact]
    public void At_NoTable_IsZero_OneEntry_IsConstant()
    {
        Assert.Equal(0, ScanOffset.At(null, 1));
        Assert.Equal(0, ScanOffset.At([], 1));
        Assert.Equal(-3, ScanOffset.At([new ScanOffset(2, -3)], 0.3));
        Assert.Equal(-3, ScanOffset.At([new ScanOffset(2, -3)], 4));
        Assert.Equal(0, MachineProfile.Default.ScanOffsetUmAt(1));
    }
}
