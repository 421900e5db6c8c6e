namespace LaserEngrave.Core.Vectors;

/// <summary>How closed shapes are burned: their outlines, scan lines filling them, or both (fill first, then outlines).</summary>
public enum VectorFillMode
{
    Outline,
    Fill,
    Both,
}
