namespace LaserEngrave.Core.Vectors;

/// <summary>A drawing as read: its paths in millimetres with y growing down (as on the stage and in images), and what was skipped.</summary>
/// <param name="Path">The file it was read from.</param>
/// <param name="Paths">Every path in drawing order.</param>
/// <param name="Warnings">One line per kind of thing skipped or assumed.</param>
/// <param name="UnitsStated">Whether the file said what its units are (DXF $INSUNITS, SVG width/height in physical units).</param>
public sealed record Drawing(string Path, IReadOnlyList<DrawingPath> Paths, IReadOnlyList<string> Warnings, bool UnitsStated)
{
    /// <summary>The smallest box around every path, found from a polyline finer than a millionth of the control points' extent.</summary>
    public (DrawingPoint Min, DrawingPoint Max) Bounds()
    {
        if (Paths.Count == 0)
        {
            throw new DrawingException($"{Path}: the drawing has nothing to burn");
        }

        var coarse = Checked(BoundsOf(Paths.SelectMany(p => p.Curves.SelectMany(c => new[] { c.Start, c.End }))));
        var extent = Math.Max(1e-9, Math.Max(coarse.Max.X - coarse.Min.X, coarse.Max.Y - coarse.Min.Y));
        return Checked(BoundsOf(Paths.SelectMany(p => p.Flatten(extent * 1e-7))));
    }

    /// <summary>The largest coordinate a drawing may have, mm (10 km): past it a transform or a number has gone wrong, and sizes turn to NaN.</summary>
    public const double MaxCoordinateMm = 1e7;

    private (DrawingPoint Min, DrawingPoint Max) Checked((DrawingPoint Min, DrawingPoint Max) box)
    {
        var worst = new[] { box.Min.X, box.Min.Y, box.Max.X, box.Max.Y }.MaxBy(v => double.IsNaN(v) ? double.PositiveInfinity : Math.Abs(v));
        return double.IsFinite(worst) && Math.Abs(worst) <= MaxCoordinateMm
            ? box
            : throw new DrawingException(string.Create(
                System.Globalization.CultureInfo.InvariantCulture,
                $"{Path}: a coordinate of {(double.IsNaN(worst) ? "NaN" : double.IsInfinity(worst) ? "infinity" : worst.ToString("G4", System.Globalization.CultureInfo.InvariantCulture))} mm is beyond the drawing limit of ±{MaxCoordinateMm:0} mm (a transform or a number too large)"));
    }

    /// <summary>The layers its paths lie on, in name order ("" for paths on no layer).</summary>
    public IReadOnlyList<string> Layers() => [.. Paths.Select(p => p.Layer).Distinct(StringComparer.Ordinal).Order(StringComparer.Ordinal)];

    private static (DrawingPoint Min, DrawingPoint Max) BoundsOf(IEnumerable<DrawingPoint> points)
    {
        double minX = double.PositiveInfinity, minY = double.PositiveInfinity, maxX = double.NegativeInfinity, maxY = double.NegativeInfinity;
        foreach (var p in points)
        {
            minX = Math.Min(minX, p.X);
            minY = Math.Min(minY, p.Y);
            maxX = Math.Max(maxX, p.X);
            maxY = Math.Max(maxY, p.Y);
        }

        return (new DrawingPoint(minX, minY), new DrawingPoint(maxX, maxY));
    }
}
