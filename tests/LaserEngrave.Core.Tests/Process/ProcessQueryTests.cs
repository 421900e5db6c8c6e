using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Process;

namespace LaserEngrave.Core.Tests.Process;

public class ProcessQueryTests
{
    [Fact]
    public void Solve_SpacingFrequencyOnePulse_SolvesSeed004Speed()
    {
        var solution = new ProcessQuery { SpacingUm = 100, FrequencyHz = 60_000, PulsesPerDot = 1 }.Solve();

        Assert.Equal(ProcessQuantity.Speed, solution.Solved);
        Assert.Equal(6000, solution.Figures.SpeedMmPerS, 9);
    }

    [Fact]
    public void Solve_SpeedAndFrequency_SolvesSpacingOverlapAndPulsesPerPixel()
    {
        // 1 mm/s / 1 kHz = 1 µm; 1 - 1/20 = 95 %; a 10 µm pixel gets 10 pulses.
        var solution = new ProcessQuery { SpeedMmPerS = 1, FrequencyHz = 1000, SpotDiameterUm = 20, PitchUm = 10 }.Solve();

        Assert.Equal(ProcessQuantity.Spacing, solution.Solved);
        Assert.Equal(1, solution.Figures.PulseSpacingUm, 12);
        Assert.Equal(95, solution.Figures.OverlapPercent, 9);
        Assert.Equal(10, solution.Figures.PulsesPerPixel!.Value, 9);
    }

    [Fact]
    public void Solve_OverlapAndSpeed_SolvesFrequency()
    {
        // 50 % of a 20 µm spot = 10 µm spacing; 2 mm/s / 10 µm = 200 Hz.
        var solution = new ProcessQuery { OverlapPercent = 50, SpeedMmPerS = 2, SpotDiameterUm = 20 }.Solve();

        Assert.Equal(ProcessQuantity.Frequency, solution.Solved);
        Assert.Equal(200, solution.Figures.FrequencyHz, 9);
        Assert.Empty(solution.Figures.Warnings);
    }

    [Fact]
    public void Solve_FrequencyNotWhole_WarnsOfTheWholeHzSent()
    {
        var solution = new ProcessQuery { SpacingUm = 3, SpeedMmPerS = 1 }.Solve();

        Assert.Equal(1000.0 / 3, solution.Figures.FrequencyHz, 9);
        Assert.Contains(solution.Figures.Warnings, w => w.Kind == JobWarningKind.FrequencyNotWhole && w.Message.Contains("333 Hz", StringComparison.Ordinal));
    }

    [Fact]
    public void Solve_AllThreeGiven_SolvesPulsesPerDot()
    {
        // 100 µm x 60 kHz / 2000 mm/s = 3 pulses per dot.
        var solution = new ProcessQuery { SpacingUm = 100, FrequencyHz = 60_000, SpeedMmPerS = 2000 }.Solve();

        Assert.Equal(ProcessQuantity.PulsesPerDot, solution.Solved);
        Assert.Equal(3, solution.Figures.PulsesPerDot);
    }

    [Fact]
    public void Solve_AllFourContradict_Throws()
    {
        var query = new ProcessQuery { SpacingUm = 100, FrequencyHz = 60_000, SpeedMmPerS = 2, PulsesPerDot = 1 };

        var error = Assert.Throws<ProcessException>(query.Solve);
        Assert.Contains("6000 mm/s", error.Message, StringComparison.Ordinal);
    }

    [Fact]
    public void Solve_FractionalPulsesPerDot_Throws()
    {
        Assert.Throws<ProcessException>(new ProcessQuery { SpacingUm = 100, FrequencyHz = 60_000, SpeedMmPerS = 2400 }.Solve);
    }

    [Theory]
    [InlineData(null, 1000.0, null)]
    [InlineData(null, null, null)]
    [InlineData(-1.0, 1000.0, null)]
    [InlineData(1.0, 0.0, null)]
    [InlineData(1.0, 1000.0, 0.0)]
    public void Solve_MissingOrBadValues_Throws(double? speed, double? frequency, double? spacing)
    {
        var query = new ProcessQuery { SpeedMmPerS = speed, FrequencyHz = frequency, SpacingUm = spacing };

        Assert.Throws<ProcessException>(query.Solve);
    }

    [Fact]
    public void Solve_SpacingAndOverlapBoth_Throws()
    {
        Assert.Throws<ProcessException>(new ProcessQuery { SpacingUm = 10, OverlapPercent = 50, SpeedMmPerS = 1 }.Solve);
    }

    [Fact]
    public void Solve_OverlapOfHundredPercent_Throws()
    {
        Assert.Throws<ProcessException>(new ProcessQuery { OverlapPercent = 100, SpeedMmPerS = 1 }.Solve);
    }
}
