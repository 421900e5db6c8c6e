namespace LaserEngrave.Wire.Scheduling;

/// <summary>Where the host's code runs: the thread pool against real ports, the simulation's loop in virtual time.</summary>
/// <remarks>
/// The one seam through which device code starts its background loops (readers, keepalive) and through which a front end
/// runs an operation on a machine. The same code then runs unchanged on real ports and, deterministically, in the twin.
/// Get one with <see cref="TaskRunner.For"/>.
/// </remarks>
public interface ITaskRunner
{
    /// <summary>Starts a loop that runs until it is stopped (a reader, a keepalive); returns its task.</summary>
    Task Start(Func<Task> loop);

    /// <summary>Runs an operation the caller waits for (a run, a test move); in a simulation, virtual time moves only while one is under way.</summary>
    Task<T> Run<T>(Func<Task<T>> operation);
}
