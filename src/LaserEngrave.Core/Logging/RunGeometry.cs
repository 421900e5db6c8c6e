using LaserEngrave.Core.Geometry;

namespace LaserEngrave.Core.Logging;

/// <summary>Where the job sat on the stage: the size asked for, the pitch, size and origin achieved, and microsteps per pixel.</summary>
/// <param name="Size">How the size was asked for (what a repeat asks for again).</param>
/// <param name="PitchUm">Pixel pitch, µm.</param>
/// <param name="MicrostepsPerPixel">Pixel pitch in microsteps, unrounded.</param>
/// <param name="MicrostepUm">Length of one microstep, µm.</param>
/// <param name="WidthMm">Width on the stage after rounding to microsteps, mm.</param>
/// <param name="HeightMm">Height on the stage after rounding to microsteps, mm.</param>
/// <param name="OriginXMm">Stage X of the image's left edge, mm.</param>
/// <param name="OriginYMm">Stage Y of the image's top edge, mm.</param>
/// <param name="ResidualScaleError">Achieved against requested size, minus 1 (see <see cref="GeometryReport"/>).</param>
public sealed record RunGeometry(
    RunSize Size,
    double PitchUm,
    double MicrostepsPerPixel,
    double MicrostepUm,
    double WidthMm,
    double HeightMm,
    double OriginXMm,
    double OriginYMm,
    double ResidualScaleError)
{
    /// <summary>The geometry of a resolved job placed at <paramref name="origin"/>.</summary>
    public static RunGeometry From(GeometryReport report, OriginMm origin)
    {
        ArgumentNullException.ThrowIfNull(report);
        return new RunGeometry(
            RunSize.From(report.Size),
            report.PitchUm,
            report.MicrostepsPerPixel,
            report.Geometry.MicrostepUm,
            report.AchievedWidthMm,
            report.AchievedHeightMm,
            origin.X,
            origin.Y,
            report.ResidualScaleError);
    }
}
