namespace LaserEngrave.Wire.Scheduling;

/// <summary>
/// A clock that also says how late the host's code wakes from a timed wait: the simulation's model of a computer busy
/// with other work (<see cref="PreciseDelay"/> adds it to every wait). On the system clock the lateness is real and
/// nothing models it.
/// </summary>
public interface IHostLateness
{
    /// <summary>How much later than asked the next timed wait ends (zero when the host is never late).</summary>
    TimeSpan NextLateness();
}
