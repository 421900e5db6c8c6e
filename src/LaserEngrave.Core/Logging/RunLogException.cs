namespace LaserEngrave.Core.Logging;

/// <summary>A run log that cannot be written, read or repeated; the message is one line naming the file and the problem.</summary>
public sealed class RunLogException : Exception
{
    public RunLogException(string message)
        : base(message)
    {
    }

    public RunLogException(string message, Exception inner)
        : base(message, inner)
    {
    }
}
