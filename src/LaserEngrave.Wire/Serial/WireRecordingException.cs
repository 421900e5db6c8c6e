namespace LaserEngrave.Wire.Serial;

/// <summary>A wire recording that cannot be read: missing, unreadable or corrupt. The message names the file (and the
/// line) and the problem in the user's words, as <c>RunLogException</c> does for the run's log; the wire codec keeps its
/// own type so that it needs nothing of Core.</summary>
public sealed class WireRecordingException : Exception
{
    public WireRecordingException(string message)
        : base(message)
    {
    }

    public WireRecordingException(string message, Exception inner)
        : base(message, inner)
    {
    }
}
