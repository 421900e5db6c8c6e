namespace LaserEngrave.Core.Vectors;

/// <summary>A drawing that cannot be read: the message names the file, the entity or element and the problem, in one line.</summary>
public sealed class DrawingException : Exception
{
    public DrawingException(string message)
        : base(message)
    {
    }

    public DrawingException(string message, Exception inner)
        : base(message, inner)
    {
    }
}
