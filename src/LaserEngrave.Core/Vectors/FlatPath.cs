namespace LaserEngrave.Core.Vectors;

/// <summary>A path flattened and placed on the stage, still unrounded (microsteps as doubles).</summary>
internal sealed record FlatPath(List<DrawingPoint> Microsteps, bool Closed, string Layer, string Source)
{
    public StagePoint RoundedStart => new(Geometry.JobGeometry.Round(Microsteps[0].X), Geometry.JobGeometry.Round(Microsteps[0].Y));

    public StagePoint RoundedEnd => new(Geometry.JobGeometry.Round(Microsteps[^1].X), Geometry.JobGeometry.Round(Microsteps[^1].Y));

    /// <summary>Every vertex rounded once to the whole microstep; repeats that rounding made are dropped.</summary>
    public StagePath ToStagePath(VectorPathKind kind)
    {
        var points = new List<StagePoint>(Microsteps.Count);
        foreach (var p in Microsteps)
        {
            var s = new StagePoint(Geometry.JobGeometry.Round(p.X), Geometry.JobGeometry.Round(p.Y));
            if (points.Count == 0 || points[^1] != s)
            {
                points.Add(s);
            }
        }

        if (points.Count == 1)
        {
            points.Add(points[0]);
        }

        return new StagePath(points, Closed && points.Count > 3, kind, Layer, Source);
    }
}
