namespace LaserEngrave.Core.Vectors;

/// <summary>One piece of a drawing's path: a line, an elliptical arc, a Bézier curve or a NURBS curve.</summary>
/// <remarks>Every curve maps exactly through an affine transform, so transforms of groups, blocks and placement never approximate.</remarks>
public interface IDrawingCurve
{
    DrawingPoint Start { get; }

    DrawingPoint End { get; }

    IDrawingCurve Transform(Affine transform);

    /// <summary>Appends the points after <see cref="Start"/> of a polyline that stays within <paramref name="tolerance"/> of the curve; the last is <see cref="End"/>.</summary>
    void Flatten(double tolerance, List<DrawingPoint> output);
}
