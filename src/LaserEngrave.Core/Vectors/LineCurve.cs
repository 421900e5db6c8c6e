namespace LaserEngrave.Core.Vectors;

/// <summary>A straight segment.</summary>
public sealed record LineCurve(DrawingPoint Start, DrawingPoint End) : IDrawingCurve
{
    public IDrawingCurve Transform(Affine transform) => new LineCurve(transform.Apply(Start), transform.Apply(End));

    public void Flatten(double tolerance, List<DrawingPoint> output) => output.Add(End);
}
