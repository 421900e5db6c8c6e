namespace LaserEngrave.Core.Geometry;

/// <summary>A size, origin or profile value from which no job geometry can be made; the message is one line naming the value.</summary>
public sealed class GeometryException : Exception
{
    public GeometryException(string message)
        : base(message)
    {
    }

    public GeometryException(string message, Exception inner)
        : base(message, inner)
    {
    }
}
