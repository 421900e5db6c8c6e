namespace LaserEngrave.Devices.Abstractions;

/// <summary>
/// What preflight asks of an axis' firmware beyond motion (<see cref="IStageAxis"/>): to clear the setting that keeps it
/// from confirming moves, and how long its replies took on the wire. A Zaber device implements it; an axis without it
/// (a fake) is neither fixed nor timed.
/// </summary>
public interface IAxisFirmware
{
    /// <summary>Clears Device Mode bit 0 (auto-reply disabled), keeping the other bits, so the axis confirms its moves again.</summary>
    Task ClearAutoReplyDisabledAsync(CancellationToken cancellationToken);

    /// <summary>How many round trips the axis' link has timed since it opened (a counter to take differences of).</summary>
    long RoundTripsRecorded { get; }

    /// <summary>The round trips, in ms, timed since <see cref="RoundTripsRecorded"/> read <paramref name="since"/>, oldest first (at most as many as the link keeps).</summary>
    List<double> RoundTripsMsSince(long since);
}
