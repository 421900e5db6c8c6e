namespace LaserEngrave.Core.Process;

/// <summary>Process values that are unusable or contradict each other; the message is one line naming them.</summary>
public sealed class ProcessException : Exception
{
    public ProcessException(string message)
        : base(message)
    {
    }

    public ProcessException(string message, Exception inner)
        : base(message, inner)
    {
    }
}
