namespace LaserEngrave.Core.Vectors;

/// <summary>One continuous path of a drawing: curves joined end to start, open or closed.</summary>
/// <param name="Curves">The pieces in drawing order; each starts where the one before it ends.</param>
/// <param name="Closed">Whether the path ends where it starts and encloses an area.</param>
/// <param name="Layer">DXF layer, or the id of the SVG group (Inkscape layer) holding it; empty when none.</param>
/// <param name="Source">Which entity or element it came from, for messages: e.g. "LWPOLYLINE (handle 2F)" or "path#outline (line 12)".</param>
public sealed record DrawingPath(IReadOnlyList<IDrawingCurve> Curves, bool Closed, string Layer, string Source)
{
    public DrawingPoint Start => Curves[0].Start;

    public DrawingPoint End => Curves[^1].End;

    public DrawingPath Transform(Affine transform) => this with { Curves = [.. Curves.Select(c => c.Transform(transform))] };

    /// <summary>The polyline within <paramref name="tolerance"/> of the path, from its start; a closed path's last point is its first.</summary>
    public List<DrawingPoint> Flatten(double tolerance)
    {
        var points = new List<DrawingPoint> { Start };
        foreach (var curve in Curves)
        {
            curve.Flatten(tolerance, points);
        }

        return points;
    }
}
