namespace LaserEngrave.Core.Marks;

/// <summary>A mark that cannot be made as asked: one line naming the value and the problem, in the user's words.</summary>
public sealed class MarkException : Exception
{
    public MarkException(string message)
        : base(message)
    {
    }

    public MarkException(string message, Exception inner)
        : base(message, inner)
    {
    }
}
