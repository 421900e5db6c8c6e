using System.Globalization;
using System.Text.Json.Serialization;

namespace LaserEngrave.Core.Geometry;

/// <summary>The stage's identified squareness and scale errors (seed 002), stored in the machine profile and compensated in every job.</summary>
/// <remarks>
/// The model (docs/calibration.md): a commanded stage displacement (sx, sy) moves the sample by
/// <c>x = (1 + kx) sx - (1 + ky) sy sin(g)</c>, <c>y = (1 + ky) sy cos(g)</c>, where kx, ky are the axes' scale errors
/// (<see cref="ScaleXPpm"/>, <see cref="ScaleYPpm"/> in parts per million) and g is <see cref="SquarenessDegrees"/>:
/// the angle from the stage's +X to its +Y direction is 90° + g. The true frame's x axis is the stage's X axis.
/// </remarks>
public sealed record AxisCalibration
{
    /// <summary>Largest squareness error accepted, degrees: beyond it the stage is broken, not out of square.</summary>
    public const double MaxSquarenessDegrees = 5;

    /// <summary>Largest scale error accepted, ppm (10 %).</summary>
    public const double MaxScalePpm = 100_000;

    /// <summary>No error: compensation is the identity.</summary>
    public static AxisCalibration None { get; } = new();

    /// <summary>Angle from +X to +Y minus 90°, degrees (positive: the axes open wider than square).</summary>
    public double SquarenessDegrees { get; init; }

    /// <summary>How much longer the X axis moves than commanded, ppm.</summary>
    public double ScaleXPpm { get; init; }

    /// <summary>How much longer the Y axis moves than commanded, ppm.</summary>
    public double ScaleYPpm { get; init; }

    /// <summary>When the calibration was solved.</summary>
    public DateTimeOffset? Date { get; init; }

    [JsonIgnore(Condition = JsonIgnoreCondition.WhenWritingNull)]
    public string? Note { get; init; }

    /// <summary>Expected (1 sigma) uncertainty of the squareness, degrees, when solved from measurements.</summary>
    [JsonIgnore(Condition = JsonIgnoreCondition.WhenWritingNull)]
    public double? SquarenessUncertaintyDegrees { get; init; }

    [JsonIgnore(Condition = JsonIgnoreCondition.WhenWritingNull)]
    public double? ScaleXUncertaintyPpm { get; init; }

    [JsonIgnore(Condition = JsonIgnoreCondition.WhenWritingNull)]
    public double? ScaleYUncertaintyPpm { get; init; }

    [JsonIgnore]
    public bool IsIdentity => SquarenessDegrees == 0 && ScaleXPpm == 0 && ScaleYPpm == 0;

    /// <summary>The machine's matrix: true displacement = M x commanded displacement, M = [[m11, m12], [0, m22]].</summary>
    public (double M11, double M12, double M22) MachineMatrix()
    {
        var g = SquarenessDegrees * Math.PI / 180;
        var ax = 1 + (ScaleXPpm * 1e-6);
        var by = 1 + (ScaleYPpm * 1e-6);
        return (ax, -by * Math.Sin(g), by * Math.Cos(g));
    }

    /// <summary>The calibration whose machine matrix is [[m11, m12], [0, m22]] (the inverse of <see cref="MachineMatrix"/>).</summary>
    public static AxisCalibration FromMachineMatrix(double m11, double m12, double m22) => new()
    {
        ScaleXPpm = (m11 - 1) * 1e6,
        ScaleYPpm = (Math.Sqrt((m12 * m12) + (m22 * m22)) - 1) * 1e6,
        SquarenessDegrees = Math.Atan2(-m12, m22) * 180 / Math.PI,
    };

    /// <summary>
    /// The machine's calibration when <paramref name="residual"/> was measured on a pattern engraved with this one
    /// compensating: the residual machine is M R = M M0⁻¹, so M = R M0 (both upper triangular, so the product is too).
    /// </summary>
    public AxisCalibration ThenResidual(AxisCalibration residual)
    {
        ArgumentNullException.ThrowIfNull(residual);
        var (a11, a12, a22) = residual.MachineMatrix();
        var (b11, b12, b22) = MachineMatrix();
        return FromMachineMatrix(a11 * b11, (a11 * b12) + (a12 * b22), a22 * b22);
    }

    /// <summary>Throws <see cref="CalibrationException"/> naming the first value out of range.</summary>
    public void Validate(string source = "calibration")
    {
        if (!double.IsFinite(SquarenessDegrees) || Math.Abs(SquarenessDegrees) > MaxSquarenessDegrees)
        {
            throw new CalibrationException($"{source}: squareness {N(SquarenessDegrees)}° must be within ±{N(MaxSquarenessDegrees)}°");
        }

        foreach (var (name, ppm) in new[] { ("scaleXPpm", ScaleXPpm), ("scaleYPpm", ScaleYPpm) })
        {
            if (!double.IsFinite(ppm) || Math.Abs(ppm) > MaxScalePpm)
            {
                throw new CalibrationException($"{source}: {name} {N(ppm)} must be within ±{N(MaxScalePpm)} ppm");
            }
        }
    }

    /// <summary>One line: angle and scales.</summary>
    public string Describe() => string.Create(
        CultureInfo.InvariantCulture,
        $"squareness {SquarenessDegrees:+0.0000;-0.0000;0}°, scale X {ScaleXPpm:+0.0;-0.0;0} ppm, scale Y {ScaleYPpm:+0.0;-0.0;0} ppm");

    private static string N(double value) => value.ToString("0.######", CultureInfo.InvariantCulture);
}
