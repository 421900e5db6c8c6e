using System.Globalization;
using LaserEngrave.Core.Calibration;
using LaserEngrave.Core.Geometry;

namespace LaserEngrave.Core.Tests.Calibration;

/// <summary>
/// The whole procedure on a synthetic machine with 0.5° squareness error, +500 ppm on X and -500 ppm on Y: engrave the
/// pattern through the real geometry, "measure" it with noise, solve, engrave it again compensated, measure the result.
/// </summary>
public class CalibrationEndToEndTests(ITestOutputHelper output)
{
    private const double InjectedDegrees = 0.5;
    private const double InjectedXPpm = 500;
    private const double InjectedYPpm = -500;

    [Fact]
    public void Calibrate_InjectedSquarenessAndScale_ResidualWithinTenMillidegreesAndFiftyPpm()
    {
        var pattern = CalibrationPattern.Create(20, 10);
        var origin = new OriginMm(10, 10);
        var noise = new Random(20261123);

        // First engraving: the machine is not calibrated yet.
        var before = Burn(pattern, MachineProfile.Default, origin);
        var measurements = Measure(pattern, before, noise);
        var solution = CalibrationSolver.Solve(measurements);
        var calibration = solution.Calibration;

        // Second engraving: the same pattern with the solved calibration in the profile.
        var after = Burn(pattern, MachineProfile.Default with { Calibration = calibration }, origin);
        var (squarenessBefore, scaleXBefore, scaleYBefore) = Errors(pattern, before);
        var (squareness, scaleX, scaleY) = Errors(pattern, after);

        var c = CultureInfo.InvariantCulture;
        output.WriteLine(string.Create(c, $"injected: {InjectedDegrees}°, X {InjectedXPpm} ppm, Y {InjectedYPpm} ppm"));
        output.WriteLine(string.Create(c, $"solved:   {calibration.SquarenessDegrees:0.00000}° ± {calibration.SquarenessUncertaintyDegrees:0.00000}°, X {calibration.ScaleXPpm:0.0} ± {calibration.ScaleXUncertaintyPpm:0.0} ppm, Y {calibration.ScaleYPpm:0.0} ± {calibration.ScaleYUncertaintyPpm:0.0} ppm"));
        output.WriteLine(string.Create(c, $"fit:      {measurements.Count} measurements, {solution.DegreesOfFreedom} dof, length rms {solution.LengthRmsUm:0.000} µm, normalized rms {solution.NormalizedRms:0.000}"));
        output.WriteLine(string.Create(c, $"before:   squareness {squarenessBefore:0.00000}°, X {scaleXBefore:0.0} ppm, Y {scaleYBefore:0.0} ppm"));
        output.WriteLine(string.Create(c, $"after:    squareness {squareness:0.00000}°, X {scaleX:0.0} ppm, Y {scaleY:0.0} ppm"));

        Assert.InRange(squarenessBefore, 0.49, 0.51);
        Assert.True(Math.Abs(squareness) <= 0.01, $"residual squareness {squareness}°");
        Assert.True(Math.Abs(scaleX) <= 50, $"residual X scale {scaleX} ppm");
        Assert.True(Math.Abs(scaleY) <= 50, $"residual Y scale {scaleY} ppm");
    }

    /// <summary>Where each feature lands on the sample, µm, true coordinates: the planner's stage positions through the faulty machine.</summary>
    private static Dictionary<string, (double X, double Y)> Burn(CalibrationPattern pattern, MachineProfile profile, OriginMm origin)
    {
        var report = GeometryResolver.Resolve(SizeSpec.Pitch(pattern.PitchUm), pattern.SidePx, pattern.SidePx, origin, profile);
        var geometry = report.Geometry;
        var w = pattern.LineWidthPx;
        var m = pattern.MarginPx;
        var s = m + w + pattern.SquareOffsetPx;
        var q = pattern.SquareSidePx;
        var features = new Dictionary<string, (double, double)>
        {
            ["crossing"] = Centre(m, m),
            ["A"] = Centre(s, s),
            ["B"] = Centre(s + q, s),
            ["C"] = Centre(s + q, s + q),
            ["D"] = Centre(s, s + q),
        };
        for (var k = 1; k <= pattern.MarkCount; k++)
        {
            features[$"x{k}"] = Centre(m + (k * pattern.MarkSpacingPx), m);
            features[$"y{k}"] = Centre(m, m + (k * pattern.MarkSpacingPx));
        }

        return features;

        // Where a vertical line of columns [column, column + w) crosses a horizontal one of rows [row, row + w): the
        // middle of the burnt runs on those rows, at the rows' mean y, in stage microsteps as the planner places them.
        (double, double) Centre(int column, int row)
        {
            double x = 0, y = 0;
            for (var r = row; r < row + w; r++)
            {
                x += (geometry.RunEdgeX(column, r) + geometry.RunEdgeX(column + w, r)) / 2.0;
                y += geometry.RowY(r);
            }

            return Machine(x / w * geometry.MicrostepUm, y / w * geometry.MicrostepUm);
        }
    }

    /// <summary>The faulty machine, written out on its own: stage X moves 1 + kx along x, stage Y moves 1 + ky at 90° + g from X.</summary>
    private static (double X, double Y) Machine(double sxUm, double syUm)
    {
        var direction = (90 + InjectedDegrees) * Math.PI / 180;
        var x = (1 + (InjectedXPpm * 1e-6)) * sxUm;
        var y = (1 + (InjectedYPpm * 1e-6)) * syUm;
        return (x + (y * Math.Cos(direction)), y * Math.Sin(direction));
    }

    /// <summary>What a technician reads off the microscope: every distance and the groove angle, each off by up to ±0.2 µm or ±0.002°.</summary>
    private static CalibrationMeasurements Measure(CalibrationPattern pattern, Dictionary<string, (double X, double Y)> at, Random noise)
    {
        double Read(string from, string to) => (Distance(at[from], at[to]) + ((noise.NextDouble() - 0.5) * 0.4)) / 1000;
        var k = pattern.MarkCount;
        return new CalibrationMeasurements
        {
            X = [.. Enumerable.Range(1, k).Select(i => new ScaleMeasurement(pattern.MarkDistanceMm(i), Read("crossing", $"x{i}")))],
            Y = [.. Enumerable.Range(1, k).Select(i => new ScaleMeasurement(pattern.MarkDistanceMm(i), Read("crossing", $"y{i}")))],
            SquareSideMm = pattern.SquareSideMm,
            SquareSidesXMm = [Read("A", "B"), Read("D", "C")],
            SquareSidesYMm = [Read("A", "D"), Read("B", "C")],
            DiagonalAcMm = Read("A", "C"),
            DiagonalBdMm = Read("B", "D"),
            GrooveAngleDegrees = Angle(at["crossing"], at[$"x{k}"], at[$"y{k}"]) + ((noise.NextDouble() - 0.5) * 0.004),
            LengthUncertaintyUm = 0.2,
            AngleUncertaintyDegrees = 0.002,
        };
    }

    /// <summary>Squareness (degrees) and scale errors (ppm) of an engraving, from the square's corners and the longest marks.</summary>
    private static (double Degrees, double XPpm, double YPpm) Errors(CalibrationPattern pattern, Dictionary<string, (double X, double Y)> at)
    {
        var k = pattern.MarkCount;
        var nominalUm = pattern.MarkDistanceMm(k) * 1000;
        var grooves = Angle(at["crossing"], at[$"x{k}"], at[$"y{k}"]) - 90;
        var square = Angle(at["A"], at["B"], at["D"]) - 90;
        var scaleX = ((Distance(at["crossing"], at[$"x{k}"]) / nominalUm) - 1) * 1e6;
        var scaleY = ((Distance(at["crossing"], at[$"y{k}"]) / nominalUm) - 1) * 1e6;
        var sideX = ((Distance(at["A"], at["B"]) / (pattern.SquareSideMm * 1000)) - 1) * 1e6;
        var sideY = ((Distance(at["A"], at["D"]) / (pattern.SquareSideMm * 1000)) - 1) * 1e6;
        return (Largest(grooves, square), Largest(scaleX, sideX), Largest(scaleY, sideY));

        static double Largest(double a, double b) => Math.Abs(a) >= Math.Abs(b) ? a : b;
    }

    private static double Distance((double X, double Y) p, (double X, double Y) q) => Math.Sqrt(((p.X - q.X) * (p.X - q.X)) + ((p.Y - q.Y) * (p.Y - q.Y)));

    /// <summary>Angle at <paramref name="vertex"/> from the direction to <paramref name="alongX"/> to the direction to <paramref name="alongY"/>, degrees.</summary>
    private static double Angle((double X, double Y) vertex, (double X, double Y) alongX, (double X, double Y) alongY)
    {
        var a = Math.Atan2(alongX.Y - vertex.Y, alongX.X - vertex.X);
        var b = Math.Atan2(alongY.Y - vertex.Y, alongY.X - vertex.X);
        return (b - a) * 180 / Math.PI;
    }
}
