namespace LaserEngrave.Simulator.Timing;

/// <summary>The simulation had nothing left to do and no timer to wait for while an operation was still under way.</summary>
public sealed class SimulationDeadlockException : Exception
{
    public SimulationDeadlockException()
    {
    }

    public SimulationDeadlockException(string message)
        : base(message)
    {
    }

    public SimulationDeadlockException(string message, Exception innerException)
        : base(message, innerException)
    {
    }
}
