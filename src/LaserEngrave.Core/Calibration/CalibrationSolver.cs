using System.Globalization;
using LaserEngrave.Core.Geometry;

namespace LaserEngrave.Core.Calibration;

/// <summary>Fits squareness and the two axis scales to the measurements by weighted least squares (Gauss-Newton).</summary>
/// <remarks>
/// Unknowns: kx, ky (scale errors) and g (squareness, radians). Model of each measurement, a = nominal square side,
/// ax = a (1 + kx), by = a (1 + ky): a distance L along X reads L (1 + kx), along Y L (1 + ky); a square side along X
/// reads ax, along Y by; diagonal AC reads sqrt(ax² + by² - 2 ax by sin g), BD sqrt(ax² + by² + 2 ax by sin g); the
/// groove angle reads 90° + g. Each residual is divided by its uncertainty, so lengths and angles weigh by how well they
/// are known. The expected uncertainty of the solution is the square root of the diagonal of (Jᵀ J)⁻¹ with J the
/// weighted Jacobian: what measurements that scatter by the stated uncertainties would give.
/// </remarks>
public static class CalibrationSolver
{
    /// <summary>Largest relative difference between a measurement and its nominal value accepted as a measurement of this pattern.</summary>
    public const double GrossErrorLimit = 0.1;

    private const int MaxIterations = 50;

    public static CalibrationSolution Solve(CalibrationMeasurements measurements)
    {
        ArgumentNullException.ThrowIfNull(measurements);
        var rows = BuildRows(measurements);
        if (rows.Count < 3)
        {
            throw new CalibrationException(
                $"{rows.Count} measurement(s) cannot determine three unknowns (squareness, X scale, Y scale): give at least one distance on each axis and the groove angle or the square's diagonals");
        }

        var theta = new double[3];
        double[,] inverse = new double[3, 3];
        for (var iteration = 0; iteration < MaxIterations; iteration++)
        {
            var normal = new double[3, 3];
            var rhs = new double[3];
            foreach (var row in rows)
            {
                var (predicted, gradient) = row.Model(theta);
                var r = (row.Measured - predicted) / row.Sigma;
                for (var i = 0; i < 3; i++)
                {
                    var gi = gradient[i] / row.Sigma;
                    rhs[i] += gi * r;
                    for (var j = 0; j < 3; j++)
                    {
                        normal[i, j] += gi * gradient[j] / row.Sigma;
                    }
                }
            }

            inverse = Invert(normal);
            var step = new double[3];
            var largest = 0.0;
            for (var i = 0; i < 3; i++)
            {
                for (var j = 0; j < 3; j++)
                {
                    step[i] += inverse[i, j] * rhs[j];
                }

                theta[i] += step[i];
                largest = Math.Max(largest, Math.Abs(step[i]));
            }

            if (largest < 1e-14)
            {
                break;
            }
        }

        if (Math.Abs(theta[2]) * 180 / Math.PI > AxisCalibration.MaxSquarenessDegrees
            || Math.Abs(theta[0]) * 1e6 > AxisCalibration.MaxScalePpm
            || Math.Abs(theta[1]) * 1e6 > AxisCalibration.MaxScalePpm)
        {
            throw new CalibrationException("the measurements give errors beyond ±5° or ±10 %: check the entries (diagonal AC is the one through the marked corner)");
        }

        var residuals = new List<MeasurementResidual>();
        double chi2 = 0, lengthSquares = 0;
        var lengths = 0;
        foreach (var row in rows)
        {
            var predicted = row.Model(theta).Value;
            var r = row.Measured - predicted;
            chi2 += r * r / (row.Sigma * row.Sigma);
            var isAngle = row.Unit == "°";
            if (!isAngle)
            {
                lengthSquares += Units.MmToUm(Units.MmToUm(r) * r);
                lengths++;
            }

            residuals.Add(new MeasurementResidual(row.Name, row.Measured, predicted, row.Unit, isAngle ? r : Units.MmToUm(r)));
        }

        var dof = rows.Count - 3;
        return new CalibrationSolution
        {
            Calibration = new AxisCalibration
            {
                ScaleXPpm = theta[0] * 1e6,
                ScaleYPpm = theta[1] * 1e6,
                SquarenessDegrees = theta[2] * 180 / Math.PI,
                ScaleXUncertaintyPpm = Math.Sqrt(inverse[0, 0]) * 1e6,
                ScaleYUncertaintyPpm = Math.Sqrt(inverse[1, 1]) * 1e6,
                SquarenessUncertaintyDegrees = Math.Sqrt(inverse[2, 2]) * 180 / Math.PI,
            },
            Residuals = residuals,
            DegreesOfFreedom = dof,
            NormalizedRms = dof > 0 ? Math.Sqrt(chi2 / dof) : null,
            LengthRmsUm = lengths > 0 ? Math.Sqrt(lengthSquares / lengths) : 0,
        };
    }

    private static List<Row> BuildRows(CalibrationMeasurements m)
    {
        if (!(m.LengthUncertaintyUm > 0) || double.IsInfinity(m.LengthUncertaintyUm))
        {
            throw new CalibrationException($"length uncertainty {N(m.LengthUncertaintyUm)} µm must be a finite number above 0");
        }

        if (!(m.AngleUncertaintyDegrees > 0) || double.IsInfinity(m.AngleUncertaintyDegrees))
        {
            throw new CalibrationException($"angle uncertainty {N(m.AngleUncertaintyDegrees)}° must be a finite number above 0");
        }

        var sigma = Units.UmToMm(m.LengthUncertaintyUm);
        var rows = new List<Row>();
        foreach (var (axis, list, index) in new[] { ("x", m.X, 0), ("y", m.Y, 1) })
        {
            foreach (var d in list)
            {
                Check(d.NominalMm, d.MeasuredMm, $"{axis} distance {N(d.NominalMm)} mm");
                var nominal = d.NominalMm;
                rows.Add(new Row($"{axis} {N(nominal)} mm", d.MeasuredMm, sigma, "mm", t => (nominal * (1 + t[index]), Unit(index, nominal))));
            }
        }

        var hasSquare = m.SquareSidesXMm.Count + m.SquareSidesYMm.Count > 0 || m.DiagonalAcMm is not null || m.DiagonalBdMm is not null;
        if (hasSquare)
        {
            var a = m.SquareSideMm ?? throw new CalibrationException("the square's nominal side is needed for its measurements");
            if (!(a > 0) || double.IsInfinity(a))
            {
                throw new CalibrationException($"square side {N(a)} mm must be a finite number above 0");
            }

            foreach (var (axis, list, index) in new[] { ("x", m.SquareSidesXMm, 0), ("y", m.SquareSidesYMm, 1) })
            {
                var k = 0;
                foreach (var side in list)
                {
                    Check(a, side, $"square side along {axis}");
                    rows.Add(new Row($"square side {axis} #{++k}", side, sigma, "mm", t => (a * (1 + t[index]), Unit(index, a))));
                }
            }

            if (m.DiagonalAcMm is { } ac)
            {
                Check(a * Math.Sqrt(2), ac, "diagonal AC");
                rows.Add(new Row("diagonal AC", ac, sigma, "mm", t => Diagonal(t, a, -1)));
            }

            if (m.DiagonalBdMm is { } bd)
            {
                Check(a * Math.Sqrt(2), bd, "diagonal BD");
                rows.Add(new Row("diagonal BD", bd, sigma, "mm", t => Diagonal(t, a, +1)));
            }
        }

        if (m.GrooveAngleDegrees is { } angle)
        {
            Check(90, angle, "groove angle");
            rows.Add(new Row("groove angle", angle, m.AngleUncertaintyDegrees, "°", t => (90 + (t[2] * 180 / Math.PI), [0, 0, 180 / Math.PI])));
        }

        return rows;
    }

    private static double[] Unit(int index, double length) => index == 0 ? [length, 0, 0] : [0, length, 0];

    /// <summary>A diagonal of the square: sign -1 for AC (shorter when g &gt; 0), +1 for BD.</summary>
    private static (double Value, double[] Gradient) Diagonal(double[] t, double a, int sign)
    {
        var ax = a * (1 + t[0]);
        var by = a * (1 + t[1]);
        var s = Math.Sin(t[2]);
        var value = Math.Sqrt((ax * ax) + (by * by) + (2 * sign * ax * by * s));
        return (value, [a * (ax + (sign * by * s)) / value, a * (by + (sign * ax * s)) / value, sign * ax * by * Math.Cos(t[2]) / value]);
    }

    private static void Check(double nominal, double measured, string what)
    {
        if (!(measured > 0) || double.IsInfinity(measured) || !(nominal > 0) || double.IsInfinity(nominal))
        {
            throw new CalibrationException($"{what}: {N(measured)} must be a finite number above 0");
        }

        if (Math.Abs((measured / nominal) - 1) > GrossErrorLimit)
        {
            throw new CalibrationException($"{what}: measured {N(measured)} is more than 10 % from the nominal {N(nominal)}; check the entry");
        }
    }

    /// <summary>Inverts a symmetric positive-definite 3 x 3 matrix; refuses when the measurements leave an unknown undetermined.</summary>
    private static double[,] Invert(double[,] a)
    {
        var det = (a[0, 0] * ((a[1, 1] * a[2, 2]) - (a[1, 2] * a[2, 1])))
            - (a[0, 1] * ((a[1, 0] * a[2, 2]) - (a[1, 2] * a[2, 0])))
            + (a[0, 2] * ((a[1, 0] * a[2, 1]) - (a[1, 1] * a[2, 0])));
        var scale = a[0, 0] * a[1, 1] * a[2, 2];
        if (!(scale > 0) || !(Math.Abs(det) > 1e-12 * scale))
        {
            throw new CalibrationException(
                "the measurements do not determine squareness, X scale and Y scale separately: give at least one distance on each axis (scale marks or square sides) and the groove angle or the square's diagonals");
        }

        var inv = new double[3, 3];
        for (var i = 0; i < 3; i++)
        {
            for (var j = 0; j < 3; j++)
            {
                int i1 = (j + 1) % 3, i2 = (j + 2) % 3, j1 = (i + 1) % 3, j2 = (i + 2) % 3;
                inv[i, j] = ((a[i1, j1] * a[i2, j2]) - (a[i1, j2] * a[i2, j1])) / det;
            }
        }

        return inv;
    }

    private static string N(double value) => value.ToString("0.######", CultureInfo.InvariantCulture);

    private sealed record Row(string Name, double Measured, double Sigma, string Unit, Func<double[], (double Value, double[] Gradient)> Model);
}
