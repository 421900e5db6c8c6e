namespace LaserEngrave.Core.Planning;

/// <summary>Plan options, process settings or a mask that cannot make a plan; the message is one line naming the value.</summary>
public sealed class PlanException : Exception
{
    public PlanException(string message)
        : base(message)
    {
    }

    public PlanException(string message, Exception inner)
        : base(message, inner)
    {
    }

    /// <summary>In a job of layers, the layer (from 0) the problem is in, so a front end can show it there; null otherwise.</summary>
    public int? Layer { get; init; }
}
