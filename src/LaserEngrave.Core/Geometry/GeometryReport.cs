namespace LaserEngrave.Core.Geometry;

/// <summary>A resolved job geometry with the figures a user checks before engraving: pitch, scale error, fit and warnings.</summary>
/// <remarks>
/// The residual scale error is what rounding leaves: the achieved extent of the image on the stage (its rounded right
/// edge minus its rounded left edge, likewise bottom minus top) against the extent asked for, as a fraction:
/// achieved / requested - 1. It is at most one microstep over the extent for a width, height, pitch or resolution;
/// with both sides given it also carries the aspect mismatch of the side that was not met exactly.
/// </remarks>
public sealed record GeometryReport
{
    /// <summary>How the size was asked for.</summary>
    public required SizeSpec Size { get; init; }

    public required JobGeometry Geometry { get; init; }

    public double PitchUm => Geometry.PitchUm;

    /// <summary>Microsteps per pixel; need not be whole.</summary>
    public double MicrostepsPerPixel => Geometry.PitchMicrosteps;

    public required double RequestedWidthMm { get; init; }

    public required double RequestedHeightMm { get; init; }

    /// <summary>Right edge minus left edge of the image on the stage after rounding, mm.</summary>
    public required double AchievedWidthMm { get; init; }

    /// <summary>Bottom edge minus top edge of the image on the stage after rounding, mm.</summary>
    public required double AchievedHeightMm { get; init; }

    /// <summary>Achieved width / requested width - 1.</summary>
    public double ScaleErrorX => (AchievedWidthMm / RequestedWidthMm) - 1;

    /// <summary>Achieved height / requested height - 1.</summary>
    public double ScaleErrorY => (AchievedHeightMm / RequestedHeightMm) - 1;

    /// <summary>The larger (in magnitude) of <see cref="ScaleErrorX"/> and <see cref="ScaleErrorY"/>, with its sign.</summary>
    public double ResidualScaleError => Math.Abs(ScaleErrorX) >= Math.Abs(ScaleErrorY) ? ScaleErrorX : ScaleErrorY;

    /// <summary>Whether the whole image (all four rounded edges) lies within 0..travel on both axes.</summary>
    public required bool FitsTravel { get; init; }

    public required IReadOnlyList<JobWarning> Warnings { get; init; }
}
