using System.Globalization;

namespace LaserEngrave.Core.Geometry;

/// <summary>Turns a requested size and origin into a <see cref="JobGeometry"/> and reports its pitch, scale error, fit and warnings.</summary>
public static class GeometryResolver
{
    /// <summary>How far apart (as a fraction) the pitches implied by a width and a height may be and still count as the image's aspect.</summary>
    public const double AspectTolerance = 0.01;

    private const double MmPerInch = 25.4;

    /// <summary>Resolves <paramref name="size"/> for an image of <paramref name="widthPx"/> x <paramref name="heightPx"/> pixels placed at <paramref name="origin"/>.</summary>
    /// <exception cref="GeometryException">A value is not usable (zero, negative, not finite), both sides disagree with the aspect, or the axes' microsteps differ.</exception>
    public static GeometryReport Resolve(SizeSpec size, int widthPx, int heightPx, OriginMm origin, MachineProfile profile)
    {
        ArgumentNullException.ThrowIfNull(size);
        ArgumentNullException.ThrowIfNull(profile);
        if (widthPx <= 0 || heightPx <= 0)
        {
            throw new GeometryException($"an image of {widthPx} x {heightPx} pixels has no area");
        }

        // The profile validator's rule; a profile built in code (never loaded) meets it here.
        if (MachineProfileValidator.EqualMicrosteps(profile) is { } unequal)
        {
            throw new GeometryException($"{profile.Name}: {unequal}");
        }

        if (!double.IsFinite(origin.X) || !double.IsFinite(origin.Y))
        {
            throw new GeometryException($"origin {N(origin.X)},{N(origin.Y)} mm is not a number");
        }

        var (pitchUm, requestedWidthMm, requestedHeightMm) = PitchAndRequestedSize(size, widthPx, heightPx);
        var microstepUm = profile.X.MicrostepUm;
        var geometry = new JobGeometry(
            widthPx,
            heightPx,
            StageUnits.UmToMicrosteps(pitchUm, microstepUm),
            StageUnits.MmToMicrosteps(origin.X, microstepUm),
            StageUnits.MmToMicrosteps(origin.Y, microstepUm),
            microstepUm,
            profile.X.TravelMicrosteps,
            profile.Y.TravelMicrosteps,
            profile.Calibration is { } calibration ? new StageCompensation(calibration) : null);

        var (left, top, right, bottom) = geometry.StageBounds();
        var fits = left >= 0 && right <= geometry.TravelXMicrosteps && top >= 0 && bottom <= geometry.TravelYMicrosteps;

        var warnings = new List<JobWarning>();
        if (geometry.PitchMicrosteps < 1)
        {
            warnings.Add(new JobWarning(
                JobWarningKind.PitchBelowMicrostep,
                $"pitch {N(pitchUm)} µm is below one microstep ({N(microstepUm)} µm): neighbouring pixel edges can land on the same microstep"));
        }

        if (!fits)
        {
            warnings.Add(new JobWarning(
                JobWarningKind.OutsideTravel,
                $"the job spans x {Mm(left)}..{Mm(right)} mm, y {Mm(top)}..{Mm(bottom)} mm but the stage travels x 0..{N(profile.X.TravelMm)} mm, y 0..{N(profile.Y.TravelMm)} mm"));
        }

        if (pitchUm < profile.SpotDiameterUm)
        {
            warnings.Add(new JobWarning(
                JobWarningKind.PitchBelowSpot,
                $"pitch {N(pitchUm)} µm is smaller than the {N(profile.SpotDiameterUm)} µm laser spot: each pixel burns wider than it is"));
        }

        return new GeometryReport
        {
            Size = size,
            Geometry = geometry,
            RequestedWidthMm = requestedWidthMm,
            RequestedHeightMm = requestedHeightMm,
            // On a calibrated machine the stage extents are mapped back to true lengths (the scale errors cancel).
            AchievedWidthMm = StageUnits.MicrostepsToMm(geometry.EdgeX(widthPx) - geometry.EdgeX(0), microstepUm) / geometry.Compensation.XPerX,
            AchievedHeightMm = StageUnits.MicrostepsToMm(bottom - top, microstepUm) / geometry.Compensation.YPerY,
            FitsTravel = fits,
            Warnings = warnings,
        };

        string Mm(long microsteps) => StageUnits.MicrostepsToMm(microsteps, microstepUm).ToString("0.###", CultureInfo.InvariantCulture);
    }

    private static (double PitchUm, double WidthMm, double HeightMm) PitchAndRequestedSize(SizeSpec size, int widthPx, int heightPx)
    {
        switch (size)
        {
            case SizeSpec.ByWidth w:
                RequirePositive(w.WidthMm, size);
                return FromPitch(Units.MmToUm(w.WidthMm) / widthPx);
            case SizeSpec.ByHeight h:
                RequirePositive(h.HeightMm, size);
                return FromPitch(Units.MmToUm(h.HeightMm) / heightPx);
            case SizeSpec.ByPitch p:
                RequirePositive(p.PitchUm, size);
                return FromPitch(p.PitchUm);
            case SizeSpec.ByResolution r:
                RequirePositive(r.Dpi, size);
                return FromPitch(Units.MmToUm(MmPerInch) / r.Dpi);
            case SizeSpec.ByWidthAndHeight b:
                RequirePositive(b.WidthMm, size);
                RequirePositive(b.HeightMm, size);
                var fromWidth = Units.MmToUm(b.WidthMm) / widthPx;
                var fromHeight = Units.MmToUm(b.HeightMm) / heightPx;
                var pitch = Math.Min(fromWidth, fromHeight);
                if ((Math.Max(fromWidth, fromHeight) / pitch) - 1 > AspectTolerance)
                {
                    throw new GeometryException(
                        $"{size.Describe()} does not match the image's aspect ({widthPx} x {heightPx} px; separate X and Y pitches are not supported): "
                        + $"{N(b.WidthMm)} x {N(b.WidthMm * heightPx / widthPx)} mm or {N(b.HeightMm * widthPx / heightPx)} x {N(b.HeightMm)} mm would; give one side only");
                }

                return (pitch, b.WidthMm, b.HeightMm);
            default:
                throw new GeometryException($"{size.Describe()}: not a size this version knows");
        }

        (double, double, double) FromPitch(double pitchUm) => (pitchUm, Units.StepsToMm(widthPx, pitchUm), Units.StepsToMm(heightPx, pitchUm));
    }

    private static void RequirePositive(double value, SizeSpec size)
    {
        if (!(value > 0) || double.IsInfinity(value))
        {
            throw new GeometryException($"{size.Describe()}: every value must be a finite number above 0");
        }
    }

    private static string N(double value) => value.ToString("0.######", CultureInfo.InvariantCulture);
}
