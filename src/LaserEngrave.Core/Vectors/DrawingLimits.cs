using System.Globalization;

namespace LaserEngrave.Core.Vectors;

/// <summary>
/// The work a drawing may ask of reading and planning, as the image decoders have their pixel limits: past any of these a
/// file is refused at once with one line naming the file and the limit, before memory or time run away. Each is far
/// above a real drawing: 300 000 LINEs or a polyline of 500 000 points plan in seconds (docs/vectors.md, "Limits").
/// </summary>
public static class DrawingLimits
{
    /// <summary>Elements or entities read, counting every copy an SVG &lt;use&gt; or a DXF INSERT (its arrays and nested blocks) makes.</summary>
    public const long MaxExpandedEntities = 2_000_000;

    /// <summary>Paths (SVG subpaths, DXF entities) in a drawing.</summary>
    public const int MaxPaths = 500_000;

    /// <summary>Curve pieces read (a polyline's segments, a path's commands).</summary>
    public const long MaxCurves = 5_000_000;

    /// <summary>Vertices once the curves are flattened within the tolerance.</summary>
    public const long MaxVertices = 10_000_000;

    /// <summary>How deep SVG elements may nest (groups in groups).</summary>
    public const int MaxNestingDepth = 256;

    /// <summary>The longest a drawing job's strokes may burn at the burn speed: each stroke's motion is modelled before the run.</summary>
    public const double MaxBurnHours = 12;

    /// <summary>The refusal for a limit passed: "FILE: [WHERE: ]more than LIMIT WHAT, the limit for a drawing; ADVICE".</summary>
    public static DrawingException Exceeded(string path, string? where, double limit, string what, string advice) =>
        new($"{path}: {(where is null ? string.Empty : where + ": ")}more than {Count(limit)} {what}, the limit for a drawing; {advice}");

    /// <summary>A count as messages show it, thousands apart by a space: 2 000 000.</summary>
    public static string Count(double value) => value.ToString("#,0", Spaced);

    private static readonly NumberFormatInfo Spaced = new() { NumberGroupSeparator = " " };
}
