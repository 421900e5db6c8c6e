using LaserEngrave.Core.Geometry;

namespace LaserEngrave.Core.Tests.Geometry;

public class JobGeometryTests
{
    private static JobGeometry Make(double pitch, double ox, double oy = 0, int width = 10, int height = 10) =>
        new(width, height, pitch, ox, oy, 0.09921875, 1_000_000, 1_000_000);

    [Fact]
    public void EdgeX_ExactHalf_RoundsAwayFromZero()
    {
        var geometry = Make(pitch: 1.5, ox: 0);
        // 1 x 1.5 = 1.5 -> 2 and 3 x 1.5 = 4.5 -> 5 (banker's rounding would give 2 and 4).
        Assert.Equal(2, geometry.EdgeX(1));
        Assert.Equal(5, geometry.EdgeX(3));
    }

    [Fact]
    public void EdgeX_NegativeHalf_RoundsAwayFromZero()
    {
        var geometry = Make(pitch: 1, ox: -2.5);
        Assert.Equal(-3, geometry.EdgeX(0));
        Assert.Equal(-2, geometry.EdgeX(1));
    }

    [Fact]
    public void RowY_Row0_IsHalfAPitchBelowTheOrigin()
    {
        var geometry = Make(pitch: 10, ox: 0, oy: 100.2);
        Assert.Equal(105, geometry.RowY(0));
        Assert.Equal(115, geometry.RowY(1));
        Assert.Equal(100, geometry.EdgeY(0));
        Assert.Equal(200, geometry.EdgeY(10));
    }

    [Fact]
    public void PitchUm_IsPitchTimesMicrostep()
    {
        Assert.Equal(0.09921875 * 8, Make(pitch: 8, ox: 0).PitchUm, 12);
    }

    [Theory]
    [InlineData(0, 10, 1.0)]
    [InlineData(10, 0, 1.0)]
    [InlineData(10, 10, 0.0)]
    [InlineData(10, 10, -1.0)]
    [InlineData(10, 10, double.NaN)]
    [InlineData(10, 10, double.PositiveInfinity)]
    public void Constructor_UnusableValue_ThrowsGeometryException(int width, int height, double pitch)
    {
        Assert.Throws<GeometryException>(() => Make(pitch, 0, 0, width, height));
    }
}
