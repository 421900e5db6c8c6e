namespace LaserEngrave.App.Services;

/// <summary>A machine command or a job change refused because another operation holds the machine; the message says which.</summary>
public sealed class MachineBusyException : InvalidOperationException
{
    public MachineBusyException(string message)
        : base(message)
    {
    }

    public MachineBusyException()
    {
    }

    public MachineBusyException(string message, Exception innerException)
        : base(message, innerException)
    {
    }
}
