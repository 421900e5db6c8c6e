using LaserEngrave.Core.Calibration;
using LaserEngrave.Core.Geometry;

namespace LaserEngrave.Core.Tests.Calibration;

public class CalibrationSolverTests
{
    private const double Side = 12;

    [Fact]
    public void Solve_ExactMeasurementsOfAKnownMachine_RecoversItsErrors()
    {
        var measurements = Measure(degrees: 0.5, xPpm: 500, yPpm: -500);

        var solution = CalibrationSolver.Solve(measurements);

        Assert.Equal(0.5, solution.Calibration.SquarenessDegrees, 9);
        Assert.Equal(500, solution.Calibration.ScaleXPpm, 5);
        Assert.Equal(-500, solution.Calibration.ScaleYPpm, 5);
        Assert.All(solution.Residuals, r => Assert.True(Math.Abs(r.Residual) < 1e-6, $"{r.Name}: {r.Residual}"));
        Assert.Equal(measurements.Count - 3, solution.DegreesOfFreedom);
    }

    [Fact]
    public void Solve_DiagonalsOnlyWithSides_RecoversNegativeSquareness()
    {
        var full = Measure(degrees: -0.2, xPpm: 0, yPpm: 300);
        var measurements = new CalibrationMeasurements
        {
            SquareSideMm = Side,
            SquareSidesXMm = full.SquareSidesXMm,
            SquareSidesYMm = full.SquareSidesYMm,
            DiagonalAcMm = full.DiagonalAcMm,
            DiagonalBdMm = full.DiagonalBdMm,
        };

        var solution = CalibrationSolver.Solve(measurements);

        Assert.Equal(-0.2, solution.Calibration.SquarenessDegrees, 9);
        Assert.Equal(300, solution.Calibration.ScaleYPpm, 5);
    }

    [Fact]
    public void Solve_OnlyXDistances_UncertaintyIsSigmaOverRootSumOfSquares()
    {
        // Least squares of m_i = L_i (1 + kx): var(kx) = sigma² / sum(L_i²). With 1 µm and L = 2, 4, 6 mm: 1e-3 / sqrt(56) = 133.6 ppm.
        var measurements = new CalibrationMeasurements
        {
            X = [new(2, 2.001), new(4, 4.002), new(6, 6.003)],
            Y = [new(10, 10)],
            GrooveAngleDegrees = 90,
            LengthUncertaintyUm = 1,
        };

        var solution = CalibrationSolver.Solve(measurements);

        Assert.Equal(1e-3 / Math.Sqrt(56) * 1e6, solution.Calibration.ScaleXUncertaintyPpm!.Value, 6);
        Assert.Equal(500, solution.Calibration.ScaleXPpm, 6);
        Assert.Equal(1e-3 / 10 * 1e6, solution.Calibration.ScaleYUncertaintyPpm!.Value, 6);
        Assert.Equal(0.01, solution.Calibration.SquarenessUncertaintyDegrees!.Value, 9);
    }

    [Fact]
    public void Solve_InconsistentMeasurement_ShowsInTheResidualAndNormalizedRms()
    {
        // Two X distances that disagree by 2 µm: least squares splits the difference weighted by length.
        var measurements = new CalibrationMeasurements
        {
            X = [new(5, 5), new(10, 10.002)],
            Y = [new(10, 10)],
            GrooveAngleDegrees = 90,
            LengthUncertaintyUm = 1,
        };

        var solution = CalibrationSolver.Solve(measurements);

        // kx = sum(L m) / sum(L²) - 1 = (25 + 100.02) / 125 - 1 = 160 ppm; residuals -0.8 µm and +0.4 µm.
        Assert.Equal(160, solution.Calibration.ScaleXPpm, 6);
        Assert.Equal(-0.8, solution.Residuals[0].Residual, 6);
        Assert.Equal(0.4, solution.Residuals[1].Residual, 6);
        Assert.Equal(Math.Sqrt((0.64 + 0.16) / 1), solution.NormalizedRms!.Value, 6);
    }

    [Fact]
    public void Solve_NoAngleInformation_Throws()
    {
        var measurements = new CalibrationMeasurements { X = [new(10, 10)], Y = [new(10, 10)], SquareSideMm = Side, SquareSidesXMm = [Side] };

        var error = Assert.Throws<CalibrationException>(() => CalibrationSolver.Solve(measurements));
        Assert.Contains("do not determine", error.Message, StringComparison.Ordinal);
    }

    [Fact]
    public void Solve_TooFewMeasurements_Throws()
    {
        Assert.Throws<CalibrationException>(() => CalibrationSolver.Solve(new CalibrationMeasurements { X = [new(10, 10)], GrooveAngleDegrees = 90 }));
    }

    [Fact]
    public void Solve_GrossTypo_Throws()
    {
        var measurements = new CalibrationMeasurements { X = [new(10, 1.0)], Y = [new(10, 10)], GrooveAngleDegrees = 90 };

        var error = Assert.Throws<CalibrationException>(() => CalibrationSolver.Solve(measurements));
        Assert.Contains("10 %", error.Message, StringComparison.Ordinal);
    }

    [Fact]
    public void Solve_SquareWithoutNominalSide_Throws()
    {
        var measurements = new CalibrationMeasurements { X = [new(10, 10)], Y = [new(10, 10)], DiagonalAcMm = 17 };

        Assert.Throws<CalibrationException>(() => CalibrationSolver.Solve(measurements));
    }

    /// <summary>Every measurement of a pattern engraved on a machine with these errors, from the corners' true positions.</summary>
    private static CalibrationMeasurements Measure(double degrees, double xPpm, double yPpm)
    {
        var g = degrees * Math.PI / 180;
        var ax = 1 + (xPpm * 1e-6);
        var by = 1 + (yPpm * 1e-6);

        // The stage's unit X and Y moves, in true coordinates: Y points 90° + g from X.
        (double X, double Y) ux = (ax, 0), uy = (by * Math.Cos((Math.PI / 2) + g), by * Math.Sin((Math.PI / 2) + g));
        (double X, double Y) At(double sx, double sy) => ((ux.X * sx) + (uy.X * sy), (ux.Y * sx) + (uy.Y * sy));
        static double Distance((double X, double Y) p, (double X, double Y) q) => Math.Sqrt(((p.X - q.X) * (p.X - q.X)) + ((p.Y - q.Y) * (p.Y - q.Y)));

        var a = At(0, 0);
        var b = At(Side, 0);
        var c = At(Side, Side);
        var d = At(0, Side);
        return new CalibrationMeasurements
        {
            X = [new(4, Distance(At(0, 0), At(4, 0))), new(16, Distance(At(0, 0), At(16, 0)))],
            Y = [new(4, Distance(At(0, 0), At(0, 4))), new(16, Distance(At(0, 0), At(0, 16)))],
            SquareSideMm = Side,
            SquareSidesXMm = [Distance(a, b), Distance(d, c)],
            SquareSidesYMm = [Distance(a, d), Distance(b, c)],
            DiagonalAcMm = Distance(a, c),
            DiagonalBdMm = Distance(b, d),
            GrooveAngleDegrees = 90 + degrees,
        };
    }
}
