using LaserEngrave.Core.Geometry;

namespace LaserEngrave.Core.Camera;

/// <summary>One known jog of the calibration: the stage's move, µm, and the picture's measured shift, pixels, with its misfit to the result.</summary>
public readonly record struct CalibrationJog(double StageDxUm, double StageDyUm, double ShiftXPx, double ShiftYPx, double MisfitUm);

/// <summary>What calibration measured: the figures to store in the profile, each jog, and the test dot's place.</summary>
public sealed record CameraCalibrationResult(CameraCalibration Calibration, IReadOnlyList<CalibrationJog> Jogs, double DotDarkeningGrey);

/// <summary>Measures the camera against the stage with the camera itself: known jogs of a feature give scale, turn and mirror; one test dot gives the spot's pixel.</summary>
/// <remarks>
/// From the start position the stage jogs three tenths of the image each way along X, Y and both diagonals (laser off) and
/// returns; each jog's picture shift is measured by <see cref="ImageRegistration"/>. A jog d moves the picture by
/// s = -M⁻¹ d, so M is the least-squares fit of d = -M s over the jogs, reduced to a scale, a turn and a mirror (the
/// part of M that is no such similarity, skew or unequal scales, shows in the residual). Then, back at the start, one
/// test dot is fired: the darkening between the images before and after it is the spot, its centroid the spot's pixel.
/// </remarks>
public sealed class CameraCalibrator
{
    private readonly ICameraRig _rig;

    public CameraCalibrator(ICameraRig rig)
    {
        ArgumentNullException.ThrowIfNull(rig);
        _rig = rig;
    }

    /// <summary>Least darkening, grey levels, by which the test dot must show.</summary>
    public const double MinDotGrey = 20;

    /// <param name="nominal">The profile's nominal figures: they size the jogs (three tenths of the image) and nothing else.</param>
    /// <param name="fireDot">Whether to fire the test dot; without it the spot's pixel is the nominal one.</param>
    /// <exception cref="CameraException">Too little texture, a jog that could not be tracked, or a dot that did not show.</exception>
    public async Task<CameraCalibrationResult> CalibrateAsync(CameraCalibration nominal, bool fireDot, CancellationToken cancellationToken, IProgress<string>? progress = null)
    {
        ArgumentNullException.ThrowIfNull(nominal);
        var (x0, y0) = _rig.Position;
        var reference = GreyImage.Of(await _rig.CaptureAsync(cancellationToken));
        if (ImageRegistration.TextureProblem(reference) is { } problem)
        {
            throw new CameraException(problem);
        }

        var jogUm = Math.Round(0.3 * Math.Min(reference.Width, reference.Height) * nominal.UmPerPixel);
        var directions = new (double X, double Y)[] { (1, 0), (-1, 0), (0, 1), (0, -1), (0.7, 0.7), (-0.7, -0.7), (0.7, -0.7), (-0.7, 0.7) };
        var measured = new List<(double Dx, double Dy, double Sx, double Sy)>();
        try
        {
            foreach (var (ux, uy) in directions)
            {
                var (dx, dy) = (Math.Round(ux * jogUm), Math.Round(uy * jogUm));
                progress?.Report($"jog {measured.Count + 1} of {directions.Length}: {dx:F0}, {dy:F0} µm");
                await _rig.MoveToAsync(x0 + dx, y0 + dy, cancellationToken);
                var (ax, ay) = _rig.Position;
                var image = GreyImage.Of(await _rig.CaptureAsync(cancellationToken));
                var shift = ImageRegistration.Measure(reference, image);
                measured.Add((ax - x0, ay - y0, shift.XPx, shift.YPx));
            }
        }
        finally
        {
            await _rig.MoveToAsync(x0, y0, CancellationToken.None);
        }

        var (umPerPixel, rotationDeg, mirrored) = FitSimilarity(measured);
        var fitted = new CameraCalibration { UmPerPixel = umPerPixel, RotationDeg = rotationDeg, Mirrored = mirrored, SpotXPx = nominal.SpotXPx, SpotYPx = nominal.SpotYPx };
        var (a, b, c, d) = fitted.Matrix();
        var jogs = measured.Select(m =>
        {
            var ex = m.Dx + (a * m.Sx) + (b * m.Sy);
            var ey = m.Dy + (c * m.Sx) + (d * m.Sy);
            return new CalibrationJog(m.Dx, m.Dy, m.Sx, m.Sy, Math.Sqrt((ex * ex) + (ey * ey)));
        }).ToList();
        var residual = Math.Sqrt(jogs.Average(j => j.MisfitUm * j.MisfitUm));
        fitted = fitted with { ResidualUm = residual };
        if (!fireDot)
        {
            return new CameraCalibrationResult(fitted, jogs, 0);
        }

        progress?.Report("test dot");
        var before = GreyImage.Of(await _rig.CaptureAsync(cancellationToken));
        await _rig.FireDotAsync(cancellationToken);
        var after = GreyImage.Of(await _rig.CaptureAsync(cancellationToken));
        var (spotX, spotY, darkening) = DotCentroid(before, after, fitted.UmPerPixel);
        return new CameraCalibrationResult(fitted with { SpotXPx = spotX, SpotYPx = spotY }, jogs, darkening);
    }

    /// <summary>Scale, turn and mirror of the least-squares M in d = -M s.</summary>
    public static (double UmPerPixel, double RotationDeg, bool Mirrored) FitSimilarity(IReadOnlyList<(double Dx, double Dy, double Sx, double Sy)> jogs)
    {
        ArgumentNullException.ThrowIfNull(jogs);
        // M = -(Σ d sᵀ)(Σ s sᵀ)⁻¹.
        double ss00 = 0, ss01 = 0, ss11 = 0, ds00 = 0, ds01 = 0, ds10 = 0, ds11 = 0;
        foreach (var (dx, dy, sx, sy) in jogs)
        {
            ss00 += sx * sx;
            ss01 += sx * sy;
            ss11 += sy * sy;
            ds00 += dx * sx;
            ds01 += dx * sy;
            ds10 += dy * sx;
            ds11 += dy * sy;
        }

        var det = (ss00 * ss11) - (ss01 * ss01);
        if (!(Math.Abs(det) > 1e-9))
        {
            throw new CameraException("the jogs moved the picture along one line only: the camera's turn cannot be measured");
        }

        var (i00, i01, i11) = (ss11 / det, -ss01 / det, ss00 / det);
        var m00 = -((ds00 * i00) + (ds01 * i01));
        var m01 = -((ds00 * i01) + (ds01 * i11));
        var m10 = -((ds10 * i00) + (ds11 * i01));
        var m11 = -((ds10 * i01) + (ds11 * i11));
        var mirrored = ((m00 * m11) - (m01 * m10)) < 0;
        if (mirrored)
        {
            // M F with F = diag(1, -1) is a plain turn and scale.
            (m01, m11) = (-m01, -m11);
        }

        var cos = (m00 + m11) / 2;
        var sin = (m10 - m01) / 2;
        return (Math.Sqrt((cos * cos) + (sin * sin)), Math.Atan2(sin, cos) * 180 / Math.PI, mirrored);
    }

    /// <summary>The centroid of what darkened between <paramref name="before"/> and <paramref name="after"/>, and by how much at most, grey levels.</summary>
    /// <remarks>
    /// A burn multiplies the sample's brightness, so the centroid weighs the share of brightness lost (1 - after / before),
    /// not the grey levels lost: a dot burnt black would otherwise lean towards the brighter grain under it.
    /// </remarks>
    public static (double XPx, double YPx, double DarkeningGrey) DotCentroid(GreyImage before, GreyImage after, double umPerPixel)
    {
        ArgumentNullException.ThrowIfNull(before);
        ArgumentNullException.ThrowIfNull(after);
        int w = before.Width, h = before.Height;
        var lost = new double[w * h];
        for (var i = 0; i < lost.Length; i++)
        {
            lost[i] = (before.Values[i] - after.Values[i]) / Math.Max(before.Values[i], 8);
        }

        // The strongest loss after a 3 x 3 mean, so one noisy pixel does not win.
        var (bestX, bestY, best) = (0, 0, double.NegativeInfinity);
        for (var y = 1; y < h - 1; y++)
        {
            for (var x = 1; x < w - 1; x++)
            {
                var sum = 0.0;
                for (var j = -1; j <= 1; j++)
                {
                    for (var i = -1; i <= 1; i++)
                    {
                        sum += lost[((y + j) * w) + x + i];
                    }
                }

                if (sum / 9 > best)
                {
                    (bestX, bestY, best) = (x, y, sum / 9);
                }
            }
        }

        var darkening = 0.0;
        for (var j = -1; j <= 1; j++)
        {
            for (var i = -1; i <= 1; i++)
            {
                darkening += (before[bestX + i, bestY + j] - after[bestX + i, bestY + j]) / 9;
            }
        }

        if (darkening < MinDotGrey)
        {
            throw new CameraException($"the test dot did not show in the image (it darkened it by {Math.Max(0, darkening):F0} grey levels at most, at least {MinDotGrey} needed): focus the camera, or fire the dot with more pulses or power");
        }

        // Weighted centroid of the loss above half the peak, within a few spot widths of it.
        var reach = Math.Max(4, (int)Math.Ceiling(60 / umPerPixel));
        double sw = 0, sx = 0, sy = 0;
        for (var y = Math.Max(0, bestY - reach); y <= Math.Min(h - 1, bestY + reach); y++)
        {
            for (var x = Math.Max(0, bestX - reach); x <= Math.Min(w - 1, bestX + reach); x++)
            {
                var weight = lost[(y * w) + x] - (best / 2);
                if (weight > 0)
                {
                    sw += weight;
                    sx += weight * x;
                    sy += weight * y;
                }
            }
        }

        return (sx / sw, sy / sw, darkening);
    }
}
