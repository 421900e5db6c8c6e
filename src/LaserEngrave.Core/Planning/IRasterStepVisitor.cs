namespace LaserEngrave.Core.Planning;

/// <summary>Receives a raster program's steps in order (<see cref="RasterProgram.Visit{TVisitor}(ref TVisitor)"/>).</summary>
/// <remarks>
/// Implement it on a struct so the calls inline. The <see cref="StrokeStep"/> passed is reused for the next stroke: it is
/// valid only during the call, so that a program of millions of strokes allocates nothing per stroke.
/// </remarks>
public interface IRasterStepVisitor
{
    void Travel(in TravelStep travel);

    void Stroke(StrokeStep stroke);

    void Move(in MoveStep move);
}
