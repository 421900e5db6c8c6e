using System.Globalization;
using LaserEngrave.Core.Geometry;

namespace LaserEngrave.Core.Vectors;

/// <summary>How a drawing becomes a vector job: size, place, chord tolerance, fill and path order.</summary>
public sealed record VectorOptions
{
    public static VectorOptions Default { get; } = new();

    /// <summary>Width of the drawing on the stage, mm (aspect kept); null keeps the drawing's own units.</summary>
    public double? WidthMm { get; init; }

    /// <summary>Where the top-left corner of the drawing's bounding box sits on the stage.</summary>
    public OriginMm Origin { get; init; } = OriginMm.Zero;

    /// <summary>Largest distance between a curve and the straight segments that replace it, µm.</summary>
    public double ToleranceUm { get; init; } = 1;

    public VectorFillMode Fill { get; init; } = VectorFillMode.Outline;

    /// <summary>Distance between the scan lines of a fill, µm.</summary>
    public double FillPitchUm { get; init; } = 20;

    /// <summary>Only the paths on this layer of the drawing are burned, placed where they are in the whole drawing; null burns every layer.</summary>
    public string? Layer { get; init; }

    /// <summary>Whether to order the paths (inner first, then shortest travel); false burns them in drawing order.</summary>
    public bool Optimize { get; init; } = true;

    /// <summary>Quarter turns clockwise on the stage, 0..3, after the mirrors; the width is the turned drawing's (as an image's).</summary>
    public int QuarterTurns { get; init; }

    /// <summary>The drawing flipped left to right in its own axes (before it is turned).</summary>
    public bool MirrorX { get; init; }

    /// <summary>The drawing flipped top to bottom in its own axes (before it is turned).</summary>
    public bool MirrorY { get; init; }

    /// <summary>
    /// The turn and mirrors as one transform of the drawing's millimetres (y downwards, as on the stage): mirrored first,
    /// then turned clockwise a quarter at a time, so an image and a drawing given the same values come out the same way round.
    /// </summary>
    public Affine Orientation()
    {
        var mirror = Affine.Scale(MirrorX ? -1 : 1, MirrorY ? -1 : 1);

        // A quarter turn clockwise with y downwards: right goes down, down goes left.
        var quarter = new Affine(0, 1, -1, 0, 0, 0);
        var turned = mirror;
        for (var i = 0; i < ((QuarterTurns % 4) + 4) % 4; i++)
        {
            turned = Affine.Compose(turned, quarter);
        }

        return turned;
    }

    /// <summary>Why a chord tolerance cannot be used, one line; null when it can (the command line and the app ask the same).</summary>
    public static string? ToleranceProblem(double toleranceUm) =>
        ToleranceAllowed(toleranceUm) ? null : $"chord tolerance {Text(toleranceUm)} µm {ToleranceRule}";

    /// <summary>Why a fill pitch cannot be used, one line; null when it can.</summary>
    public static string? FillPitchProblem(double fillPitchUm) =>
        FillPitchAllowed(fillPitchUm) ? null : $"fill pitch {Text(fillPitchUm)} µm {FillPitchRule}";

    /// <summary>The chord tolerance's range, as the job rules say it.</summary>
    public const string ToleranceRule = "must be between 0.01 and 1000 µm";

    /// <summary>The fill pitch's range, as the job rules say it.</summary>
    public const string FillPitchRule = "must be between 0.1 and 10000 µm";

    public static bool ToleranceAllowed(double toleranceUm) => toleranceUm is >= 0.01 and <= 1000;

    public static bool FillPitchAllowed(double fillPitchUm) => fillPitchUm is >= 0.1 and <= 10_000;

    /// <summary>Throws a <see cref="GeometryException"/> naming the first unusable value.</summary>
    public void Validate()
    {
        if (WidthMm is { } w && !(w > 0 && double.IsFinite(w)))
        {
            throw new GeometryException($"width {Text(w)} mm must be above 0");
        }

        if (ToleranceProblem(ToleranceUm) is { } tolerance)
        {
            throw new GeometryException(tolerance);
        }

        if (FillPitchProblem(FillPitchUm) is { } pitch)
        {
            throw new GeometryException(pitch);
        }

        if (QuarterTurns is < 0 or > 3)
        {
            throw new GeometryException($"quarter turns {QuarterTurns} must be 0, 1, 2 or 3 (0°, 90°, 180°, 270° clockwise)");
        }

        if (!double.IsFinite(Origin.X) || !double.IsFinite(Origin.Y))
        {
            throw new GeometryException($"origin {Text(Origin.X)}, {Text(Origin.Y)} mm must be finite");
        }
    }

    private static string Text(double v) => v.ToString(CultureInfo.InvariantCulture);
}
