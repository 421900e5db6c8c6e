using LaserEngrave.Core.Geometry;

namespace LaserEngrave.Core.Tests.Geometry;

public class GeometryResolverTests
{
    private const double Microstep = 0.09921875;

    private static readonly MachineProfile Profile = MachineProfile.Default;

    [Fact]
    public void Resolve_10MmOver180Px_PitchIs55Point56UmAnd559Point93Microsteps()
    {
        // Seed 000's example, the right way round: 10 mm / 180 px = 55.56 µm = 559.93 microsteps.
        var report = GeometryResolver.Resolve(SizeSpec.Width(10), 180, 90, OriginMm.Zero, Profile);
        Assert.Equal(10000.0 / 180, report.PitchUm, 9);
        Assert.Equal(559.93, report.MicrostepsPerPixel, 2);
        Assert.Equal(5, report.RequestedHeightMm, 9);
    }

    [Fact]
    public void Resolve_Width_ScaleErrorIsTheRoundingOfTheRightEdge()
    {
        var report = GeometryResolver.Resolve(SizeSpec.Width(10), 180, 90, OriginMm.Zero, Profile);
        // 10 mm = 100787.40 microsteps, rounded to 100787: achieved 100787 x 0.09921875 µm.
        var achievedMm = (double)(100787m * 0.09921875m / 1000m);
        Assert.Equal(achievedMm, report.AchievedWidthMm, 12);
        Assert.Equal((achievedMm / 10) - 1, report.ScaleErrorX, 12);
        Assert.InRange(Math.Abs(report.ScaleErrorX), 1e-9, 0.5 * Microstep / 10000);
        Assert.InRange(Math.Abs(report.ScaleErrorY), 1e-9, 0.5 * Microstep / 5000);
        Assert.Equal(Math.Max(Math.Abs(report.ScaleErrorX), Math.Abs(report.ScaleErrorY)), Math.Abs(report.ResidualScaleError));
    }

    [Fact]
    public void Resolve_Height_WidthFollowsTheAspect()
    {
        var report = GeometryResolver.Resolve(SizeSpec.Height(20), 300, 200, OriginMm.Zero, Profile);
        Assert.Equal(100, report.PitchUm, 9);
        Assert.Equal(30, report.RequestedWidthMm, 9);
    }

    [Fact]
    public void Resolve_Pitch_UsesItAsGiven()
    {
        var report = GeometryResolver.Resolve(SizeSpec.Pitch(Microstep * 7), 10, 10, OriginMm.Zero, Profile);
        Assert.Equal(7, report.MicrostepsPerPixel, 9);
        Assert.Equal(0, report.ResidualScaleError, 9);
    }

    [Fact]
    public void Resolve_254Dpi_Is100Um()
    {
        var report = GeometryResolver.Resolve(SizeSpec.Resolution(254), 10, 10, OriginMm.Zero, Profile);
        Assert.Equal(100, report.PitchUm, 9);
    }

    [Fact]
    public void Resolve_Origin_PlacesTheLeftEdge()
    {
        var report = GeometryResolver.Resolve(SizeSpec.Pitch(50), 10, 10, new OriginMm(1, 2), Profile);
        // 1 mm = 10078.74 microsteps, 2 mm = 20157.48.
        Assert.Equal(10079, report.Geometry.EdgeX(0));
        Assert.Equal(20157, report.Geometry.EdgeY(0));
    }

    [Fact]
    public void Resolve_BothSidesInTheAspect_UsesTheSmallerPitch()
    {
        var report = GeometryResolver.Resolve(SizeSpec.WidthAndHeight(10, 10.05), 100, 100, OriginMm.Zero, Profile);
        Assert.Equal(100, report.PitchUm, 9);
        Assert.Equal(10.05, report.RequestedHeightMm, 9);
        Assert.True(report.ScaleErrorY < -0.004, $"the height falls short of 10.05 mm: {report.ScaleErrorY}");
    }

    [Fact]
    public void Resolve_BothSidesOffTheAspect_RefusesAndSuggestsMatchingSizes()
    {
        var ex = Assert.Throws<GeometryException>(() =>
            GeometryResolver.Resolve(SizeSpec.WidthAndHeight(10, 5), 41, 41, OriginMm.Zero, Profile));
        Assert.Contains("10 x 5 mm", ex.Message, StringComparison.Ordinal);
        Assert.Contains("10 x 10 mm", ex.Message, StringComparison.Ordinal);
        Assert.Contains("5 x 5 mm", ex.Message, StringComparison.Ordinal);
    }

    [Theory]
    [InlineData(0.0)]
    [InlineData(-3.0)]
    [InlineData(double.NaN)]
    [InlineData(double.PositiveInfinity)]
    public void Resolve_UnusableWidth_ThrowsNamingIt(double widthMm)
    {
        var ex = Assert.Throws<GeometryException>(() => GeometryResolver.Resolve(SizeSpec.Width(widthMm), 10, 10, OriginMm.Zero, Profile));
        Assert.Contains("width", ex.Message, StringComparison.Ordinal);
    }

    [Fact]
    public void Resolve_NaNOrigin_Throws()
    {
        Assert.Throws<GeometryException>(() => GeometryResolver.Resolve(SizeSpec.Width(1), 10, 10, new OriginMm(double.NaN, 0), Profile));
    }

    [Fact]
    public void Resolve_AxesWithDifferentMicrosteps_Throws()
    {
        var profile = Profile with { Y = Profile.Y with { MicrostepUm = 0.2 } };
        var ex = Assert.Throws<GeometryException>(() => GeometryResolver.Resolve(SizeSpec.Width(1), 10, 10, OriginMm.Zero, profile));
        Assert.Contains("microstep", ex.Message, StringComparison.Ordinal);
    }

    [Fact]
    public void Resolve_InsideTravel_FitsWithoutWarnings()
    {
        var report = GeometryResolver.Resolve(SizeSpec.Width(10), 100, 100, new OriginMm(5, 5), Profile);
        Assert.True(report.FitsTravel);
        Assert.Empty(report.Warnings);
    }

    [Theory]
    [InlineData(55.0, 5.0)]
    [InlineData(5.0, 55.0)]
    [InlineData(-0.1, 5.0)]
    public void Resolve_PastTheTravel_DoesNotFitAndWarns(double originX, double originY)
    {
        var report = GeometryResolver.Resolve(SizeSpec.Width(10), 100, 100, new OriginMm(originX, originY), Profile);
        Assert.False(report.FitsTravel);
        var warning = Assert.Single(report.Warnings);
        Assert.Equal(JobWarningKind.OutsideTravel, warning.Kind);
        Assert.Contains("60 mm", warning.Message, StringComparison.Ordinal);
    }

    [Fact]
    public void Resolve_ExactlyTheTravel_Fits()
    {
        // 604724 microsteps is the last whole one within 60 mm.
        var report = GeometryResolver.Resolve(SizeSpec.Pitch(604724 * Microstep / 4), 4, 4, OriginMm.Zero, Profile);
        Assert.True(report.FitsTravel);
    }

    [Fact]
    public void Resolve_PitchBelowOneMicrostep_Warns()
    {
        var report = GeometryResolver.Resolve(SizeSpec.Pitch(0.05), 10, 10, new OriginMm(1, 1), Profile with { SpotDiameterUm = 0.01 });
        var warning = Assert.Single(report.Warnings);
        Assert.Equal(JobWarningKind.PitchBelowMicrostep, warning.Kind);
    }

    [Fact]
    public void Resolve_PitchBelowTheSpot_Warns()
    {
        var report = GeometryResolver.Resolve(SizeSpec.Pitch(10), 10, 10, new OriginMm(1, 1), Profile with { SpotDiameterUm = 20 });
        var warning = Assert.Single(report.Warnings);
        Assert.Equal(JobWarningKind.PitchBelowSpot, warning.Kind);
        Assert.Contains("20 µm", warning.Message, StringComparison.Ordinal);
    }
}
