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
}
