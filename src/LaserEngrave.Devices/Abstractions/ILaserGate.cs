namespace LaserEngrave.Devices.Abstractions;

/// <summary>The PIC that gates the laser's Q-switch: f Hz fires f pulses per second, 0 stops it.</summary>
public interface ILaserGate
{
    /// <summary>Asks the gate who it is; returns its identification text.</summary>
    Task<string> IdentifyAsync(CancellationToken cancellationToken);

    /// <summary>Fires at <paramref name="frequencyHz"/> pulses per second (0 = off); waits for the acknowledgement.</summary>
    Task SetFrequencyAsync(int frequencyHz, CancellationToken cancellationToken);

    /// <summary>Stops firing; waits for the acknowledgement.</summary>
    Task OffAsync(CancellationToken cancellationToken);

    Task<LaserGateState> GetStateAsync(CancellationToken cancellationToken);

    /// <summary>Feeds the gate's watchdog.</summary>
    Task KeepAliveAsync(CancellationToken cancellationToken);

    /// <summary>Sets the watchdog time in ms (0 = disabled).</summary>
    Task SetWatchdogAsync(int milliseconds, CancellationToken cancellationToken);

    /// <summary>Fires <paramref name="pulses"/> pulses at <paramref name="frequencyHz"/>, then stops by itself.</summary>
    Task BurstAsync(int pulses, int frequencyHz, CancellationToken cancellationToken);
}

/// <summary>What the gate reports about itself.</summary>
public sealed record LaserGateState(int FrequencyHz, bool Firing, int WatchdogMs, bool WatchdogTripped);
