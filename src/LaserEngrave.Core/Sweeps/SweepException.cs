namespace LaserEngrave.Core.Sweeps;

/// <summary>A sweep that cannot be planned, with one line naming the value and the problem.</summary>
public sealed class SweepException : Exception
{
    public SweepException(string message)
        : base(message)
    {
    }

    public SweepException(string message, Exception inner)
        : base(message, inner)
    {
    }
}
