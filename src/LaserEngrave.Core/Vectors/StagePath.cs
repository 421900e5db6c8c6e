namespace LaserEngrave.Core.Vectors;

/// <summary>One path as the stage burns it: vertices in whole microsteps, each rounded once from its absolute position.</summary>
/// <param name="Points">The vertices in burn order; a closed path's last point is its first.</param>
/// <param name="Closed">Whether the path is a closed contour (it may start at any of its vertices).</param>
/// <param name="Kind">Outline or fill scan line.</param>
/// <param name="Layer">The drawing's layer, empty when none.</param>
/// <param name="Source">The entity or element it came from.</param>
public sealed record StagePath(IReadOnlyList<StagePoint> Points, bool Closed, VectorPathKind Kind, string Layer, string Source)
{
    public StagePoint Start => Points[0];

    public StagePoint End => Points[^1];

    /// <summary>Length along the vertices, in microsteps.</summary>
    public double LengthMicrosteps
    {
        get
        {
            var length = 0.0;
            for (var i = 1; i < Points.Count; i++)
            {
                length += StagePoint.Distance(Points[i - 1], Points[i]);
            }

            return length;
        }
    }

    /// <summary>The same path burned the other way.</summary>
    public StagePath Reversed() => this with { Points = [.. Points.Reverse()] };

    /// <summary>A closed path started (and ended) at vertex <paramref name="index"/>.</summary>
    public StagePath StartingAt(int index)
    {
        if (!Closed || index == 0)
        {
            return this;
        }

        var n = Points.Count - 1;
        var rotated = new StagePoint[n + 1];
        for (var i = 0; i < n; i++)
        {
            rotated[i] = Points[(index + i) % n];
        }

        rotated[n] = rotated[0];
        return this with { Points = rotated };
    }
}
