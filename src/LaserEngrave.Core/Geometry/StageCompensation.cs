using LaserEngrave.Core.Geometry;

namespace LaserEngrave.Core.Geometry;

/// <summary>The inverse of the machine's error: which stage displacement gives a wanted true displacement.</summary>
/// <remarks>
/// With the machine matrix M = [[ax, -by sin g], [0, by cos g]] of <see cref="AxisCalibration"/>, the stage displacement
/// for a true displacement (dx, dy) is M⁻¹ (dx, dy): <c>sy = dy / (by cos g)</c>, <c>sx = (dx + dy tan g) / ax</c>.
/// sy depends on dy alone, so a row along true x is a row along stage X: rows stay single-axis moves exactly, each row
/// shifted along X by its y times tan g / ax. The factors are kept per pixel so edges are one fused multiply-add each.
/// </remarks>
public sealed record StageCompensation
{
    public StageCompensation(AxisCalibration calibration)
    {
        ArgumentNullException.ThrowIfNull(calibration);
        Calibration = calibration;
        var (m11, m12, m22) = calibration.MachineMatrix();
        XPerX = 1 / m11;
        XPerY = -m12 / (m11 * m22);
        YPerY = 1 / m22;
    }

    public static StageCompensation Identity { get; } = new(AxisCalibration.None);

    public AxisCalibration Calibration { get; }

    /// <summary>Stage X per unit of true x: 1 / ax.</summary>
    public double XPerX { get; }

    /// <summary>Stage X per unit of true y: tan g / ax.</summary>
    public double XPerY { get; }

    /// <summary>Stage Y per unit of true y: 1 / (by cos g).</summary>
    public double YPerY { get; }

    public bool IsIdentity => Calibration.IsIdentity;

    /// <summary>The stage displacement that moves the sample by (dx, dy) in true coordinates.</summary>
    public (double X, double Y) ToStage(double dx, double dy) => ((dx * XPerX) + (dy * XPerY), dy * YPerY);

    /// <summary>The true displacement a stage displacement gives on this machine (the machine model itself).</summary>
    public (double X, double Y) ToTrue(double sx, double sy)
    {
        var (m11, m12, m22) = Calibration.MachineMatrix();
        return ((m11 * sx) + (m12 * sy), m22 * sy);
    }
}
