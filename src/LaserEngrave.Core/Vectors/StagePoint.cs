namespace LaserEngrave.Core.Vectors;

/// <summary>A position sent to the stage: whole microsteps on each axis.</summary>
public readonly record struct StagePoint(long X, long Y)
{
    public static double Distance(StagePoint a, StagePoint b)
    {
        double dx = a.X - b.X, dy = a.Y - b.Y;
        return Math.Sqrt((dx * dx) + (dy * dy));
    }
}
