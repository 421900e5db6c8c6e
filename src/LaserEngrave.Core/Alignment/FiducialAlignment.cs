using System.Globalization;
using LaserEngrave.Core.Calibration;
using LaserEngrave.Core.Geometry;

namespace LaserEngrave.Core.Alignment;

/// <summary>The rigid transform two fiducial marks give, with the check of their distance (like LightBurn's print-and-cut).</summary>
public sealed record FiducialAlignment
{
    /// <summary>Default largest accepted difference between the marks' measured and nominal distance, µm.</summary>
    public const double DefaultToleranceUm = 50;

    /// <summary>Marks closer than this in the job give too poor an angle, mm.</summary>
    public const double MinSeparationMm = 1;

    /// <summary>From job coordinates to true sample coordinates (on an uncalibrated machine, stage coordinates), mm.</summary>
    public required RigidTransform Transform { get; init; }

    /// <summary>Measured distance between the marks over their nominal distance, minus 1, ppm: the scale the rigid fit ignores.</summary>
    public required double ScaleMismatchPpm { get; init; }

    /// <summary>Measured minus nominal distance between the marks, µm.</summary>
    public required double DistanceMismatchUm { get; init; }

    /// <summary>Distance from each mark's measured position to where the transform puts it, µm (both half the mismatch).</summary>
    public required double ResidualUm { get; init; }

    /// <summary>
    /// Solves the rotation from the direction between the marks and the translation from their midpoint, so each mark
    /// is off by half the distance mismatch. On a calibrated machine the stage positions are first mapped to true
    /// coordinates (true = M stage, about the stage's zero), so the alignment and the compensation agree.
    /// </summary>
    /// <exception cref="AlignmentException">The marks are less than 1 mm apart in the job, or their distances differ by more than the tolerance.</exception>
    public static FiducialAlignment Solve(Fiducial first, Fiducial second, double toleranceUm = DefaultToleranceUm, AxisCalibration? calibration = null)
    {
        foreach (var value in new[] { first.JobXMm, first.JobYMm, first.StageXMm, first.StageYMm, second.JobXMm, second.JobYMm, second.StageXMm, second.StageYMm, toleranceUm })
        {
            if (!double.IsFinite(value))
            {
                throw new AlignmentException("every mark position and the tolerance must be finite numbers");
            }
        }

        var compensation = new StageCompensation(calibration ?? AxisCalibration.None);
        var (m1x, m1y) = compensation.ToTrue(first.StageXMm, first.StageYMm);
        var (m2x, m2y) = compensation.ToTrue(second.StageXMm, second.StageYMm);
        double njx = second.JobXMm - first.JobXMm, njy = second.JobYMm - first.JobYMm;
        double mdx = m2x - m1x, mdy = m2y - m1y;
        var nominal = Math.Sqrt((njx * njx) + (njy * njy));
        var measured = Math.Sqrt((mdx * mdx) + (mdy * mdy));
        if (nominal < MinSeparationMm)
        {
            throw new AlignmentException($"the marks are {N(nominal)} mm apart in the job; pick two at least {N(MinSeparationMm)} mm apart (farther is better)");
        }

        var mismatchUm = Units.MmToUm(measured - nominal);
        if (!(Math.Abs(mismatchUm) <= toleranceUm))
        {
            throw new AlignmentException(
                $"the marks are {N(measured)} mm apart on the stage but {N(nominal)} mm in the job ({N(mismatchUm)} µm off, tolerance {N(toleranceUm)} µm): a mark was found wrongly, or its job position is wrong");
        }

        var angle = Math.Atan2(mdy, mdx) - Math.Atan2(njy, njx);
        angle = Math.IEEERemainder(angle, 2 * Math.PI);
        var (s, c) = Math.SinCos(angle);
        double jcx = (first.JobXMm + second.JobXMm) / 2, jcy = (first.JobYMm + second.JobYMm) / 2;
        double mcx = (m1x + m2x) / 2, mcy = (m1y + m2y) / 2;
        var transform = new RigidTransform(angle, mcx - ((c * jcx) - (s * jcy)), mcy - ((s * jcx) + (c * jcy)));
        return new FiducialAlignment
        {
            Transform = transform,
            ScaleMismatchPpm = ((measured / nominal) - 1) * 1e6,
            DistanceMismatchUm = mismatchUm,
            ResidualUm = Math.Abs(mismatchUm) / 2,
        };
    }

    private static string N(double value) => value.ToString("0.####", CultureInfo.InvariantCulture);
}
