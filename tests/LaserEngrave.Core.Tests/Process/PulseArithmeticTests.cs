using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Planning;
using LaserEngrave.Core.Process;

namespace LaserEngrave.Core.Tests.Process;

public class PulseArithmeticTests
{
    [Fact]
    public void SpeedMmPerS_Seed004Line_SixMetresPerSecond()
    {
        // Seed 004: 0.1 mm x 60 kHz / 1 = 6 m/s.
        Assert.Equal(6000, PulseArithmetic.SpeedMmPerS(spacingUm: 100, frequencyHz: 60_000, pulsesPerDot: 1), 9);
    }

    [Fact]
    public void SpeedMmPerS_ThreePulsesPerDot_ThirdOfTheSpeed()
    {
        Assert.Equal(2000, PulseArithmetic.SpeedMmPerS(100, 60_000, 3), 9);
    }

    [Fact]
    public void GridUnitUm_Seed004Field_OnePointSixEightMicrometres()
    {
        // Seed 004: 110 mm / 65536 = 1.68 µm, and 100 µm -> 59.6 -> 60 units.
        var unit = PulseArithmetic.GridUnitUm(110, 65536);
        Assert.Equal(1.68, unit, 2);
        Assert.Equal(1.678466796875, unit, 12);
        Assert.Equal(60, PulseArithmetic.ToGridUnits(100, unit));
    }

    [Fact]
    public void SpacingUm_OneMmPerSAtOneKilohertz_OneMicrometre()
    {
        Assert.Equal(1.0, PulseArithmetic.SpacingUm(1, 1000), 12);
    }

    [Fact]
    public void FrequencyHz_InverseOfSpacing_RoundTrips()
    {
        Assert.Equal(60_000, PulseArithmetic.FrequencyHz(6000, 100), 6);
        Assert.Equal(3, PulseArithmetic.PulsesPerDot(2000, 60_000, 100), 12);
    }

    [Fact]
    public void Overlap_HalfSpotSpacing_FiftyPercent()
    {
        Assert.Equal(0.5, PulseArithmetic.Overlap(10, 20), 12);
        Assert.Equal(-4.0, PulseArithmetic.Overlap(100, 20), 12);
        Assert.Equal(10, PulseArithmetic.SpacingForOverlap(0.5, 20), 12);
    }

    [Fact]
    public void For_DefaultProcessAndPitch_SpacingOverlapPulsesAndEnergy()
    {
        // 1 mm/s at 1 kHz: 1 µm apart; 20 µm spot: 95 % overlap; 39.37 µm pixel: 39.37 pulses; 5 µJ each: 196.85 µJ.
        var figures = PulseFigures.For(ProcessSettings.Default with { PulseEnergyUj = 5 }, spotDiameterUm: 20, pitchUm: 39.37);

        Assert.Equal(1.0, figures.PulseSpacingUm, 12);
        Assert.Equal(95.0, figures.OverlapPercent, 9);
        Assert.Equal(39.37, figures.PulsesPerPixel!.Value, 9);
        Assert.Equal(196.85, figures.EnergyPerPixelUj!.Value, 9);
        Assert.Empty(figures.Warnings);
    }

    [Fact]
    public void For_SpacingAboveSpot_WarnsOfGaps()
    {
        var figures = PulseFigures.For(speedMmPerS: 30, frequencyHz: 1000, spotDiameterUm: 20);

        Assert.Equal(30, figures.PulseSpacingUm, 12);
        var warning = Assert.Single(figures.Warnings);
        Assert.Equal(JobWarningKind.PulseGaps, warning.Kind);
        Assert.Contains("20 mm/s", warning.Message, StringComparison.Ordinal);
    }

    [Fact]
    public void For_PixelSmallerThanSpacing_WarnsOfPixelsWithoutPulses()
    {
        var figures = PulseFigures.For(speedMmPerS: 10, frequencyHz: 1000, spotDiameterUm: 20, pitchUm: 5);

        Assert.Equal(0.5, figures.PulsesPerPixel!.Value, 12);
        Assert.Contains(figures.Warnings, w => w.Kind == JobWarningKind.PixelUnderOnePulse);
        Assert.DoesNotContain(figures.Warnings, w => w.Kind == JobWarningKind.PulseGaps);
    }

    [Fact]
    public void For_NoPitch_NoPixelFigures()
    {
        var figures = PulseFigures.For(1, 1000, 20, pulseEnergyUj: 3);

        Assert.Null(figures.PulsesPerPixel);
        Assert.Null(figures.EnergyPerPixelUj);
    }

    [Fact]
    public void ForDots_DotAtEveryPixel_NPulsesAPixel()
    {
        // 10 pulses at 1 kHz on dots 121.95 µm apart (a 5 mm QR code of 41 px): 10 a pixel; mean speed 121.95 µm x 1000 / 10.
        var figures = PulseFigures.ForDots(10, 1000, 5000.0 / 41, 20, 5000.0 / 41, pulseEnergyUj: 5);

        Assert.Equal(10, figures.PulsesPerPixel!.Value, 12);
        Assert.Equal(50, figures.EnergyPerPixelUj!.Value, 12);
        Assert.Equal(5000.0 / 41 / 1000 * 1000 / 10, figures.SpeedMmPerS, 12);
        Assert.Contains(figures.Warnings, w => w.Kind == JobWarningKind.PulseGaps);
    }

    [Fact]
    public void ForDots_DotPitchAQuarterPixel_FourDotsOfNPulses()
    {
        // Dots 12.5 µm apart on 50 µm pixels, 3 pulses each: 12 pulses a pixel; 1 - 12.5 / 20 = 37.5 % overlap.
        var figures = PulseFigures.ForDots(3, 1000, 12.5, 20, 50);

        Assert.Equal(12, figures.PulsesPerPixel!.Value, 12);
        Assert.Equal(37.5, figures.OverlapPercent, 12);
        Assert.Empty(figures.Warnings);
    }
}
