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

    /// <summary>
    /// Fires <paramref name="pulses"/> pulses at <paramref name="frequencyHz"/>, the first <paramref name="afterUs"/> µs after
    /// the line's last byte has arrived at the gate, timed by the gate itself (docs/laser-gate-protocol.md, "Scheduled
    /// bursts"); waits for the acknowledgement, which the gate sends when it has accepted the line, before the first pulse.
    /// Only for a gate whose <see cref="GetCapabilitiesAsync"/> lists <see cref="LaserGateCapabilities.After"/>; a link that
    /// cannot send it fails.
    /// </summary>
    Task BurstAfterAsync(int pulses, int frequencyHz, int afterUs, CancellationToken cancellationToken) =>
        Task.FromException(new NotSupportedException("this laser gate link cannot send a scheduled burst"));

    /// <summary>
    /// Completes when the line of the command asked for last (the call that returned just before this is read) has been
    /// written, with the time its write completed (returned from the operating system) as a timestamp of the gate's clock
    /// (the machine's); null when it was never written or the link cannot tell. A computer that stalled between deciding
    /// to send and the write sent the line that much later, whatever was planned.
    /// </summary>
    Task<long?> LineWritten => Task.FromResult<long?>(null);

    /// <summary>True while bytes that arrived from the gate are still on their way to the host's code; false when the link cannot tell.</summary>
    bool IsReceiving => false;

    /// <summary>What the gate can do beyond the base protocol (its answer to CAPS?); none for a gate that refuses the question.</summary>
    Task<IReadOnlySet<string>> GetCapabilitiesAsync(CancellationToken cancellationToken) =>
        Task.FromResult<IReadOnlySet<string>>(new HashSet<string>());

    /// <summary>
    /// Sends one command of the emergency off (<see cref="Execution.LaserOff"/>) at once, whatever the link's state: ahead of
    /// every ordinary command waiting to be sent and without first getting the link back in step after a timeout (a
    /// keepalive sent first would only feed the watchdog the off counts on); waits for the acknowledgement.
    /// </summary>
    Task EmergencyAsync(EmergencyCommand command, CancellationToken cancellationToken);

    /// <summary>
    /// Closes the gate's port: the gate hears nothing more, so its own watchdog switches the laser off (the last resort of
    /// the emergency off); every command waiting fails, and every later one too. Closing twice does nothing more.
    /// </summary>
    ValueTask CloseAsync();
}

/// <summary>The commands of the emergency off, each a way to stop the laser on its own.</summary>
public enum EmergencyCommand
{
    /// <summary>OFF.</summary>
    Off,

    /// <summary>FREQ 0.</summary>
    FrequencyZero,

    /// <summary>The shortest watchdog the profile rules allow (<see cref="Core.Geometry.MachineProfileValidator.MinWatchdogMs"/> ms), so a gate that hears nothing more stops soonest.</summary>
    ShortestWatchdog,
}

/// <summary>The words a gate's CAPS? reply may list.</summary>
public static class LaserGateCapabilities
{
    /// <summary>The scheduled burst, BURST n hz AFTER us.</summary>
    public const string After = "AFTER";
}

/// <summary>What the gate reports about itself.</summary>
public sealed record LaserGateState(int FrequencyHz, bool Firing, int WatchdogMs, bool WatchdogTripped);
