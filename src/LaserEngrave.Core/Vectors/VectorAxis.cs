namespace LaserEngrave.Core.Vectors;

/// <summary>One of the stage's two axes, as a vector stroke addresses them.</summary>
public enum VectorAxis
{
    X,
    Y,
}
