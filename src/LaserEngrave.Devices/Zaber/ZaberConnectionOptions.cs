namespace LaserEngrave.Devices.Zaber;

/// <summary>Timing of a Zaber chain connection; the defaults suit T-series devices at 9600 baud.</summary>
public sealed record ZaberConnectionOptions
{
    /// <summary>Bytes of an unfinished frame older than this are dropped, as the devices do (Zaber's 10 ms rule).</summary>
    /// <remarks>A USB adapter that delivers a frame in pieces further apart (FTDI latency timer) needs a larger value.</remarks>
    public TimeSpan PartialFrameTimeout { get; init; } = TimeSpan.FromMilliseconds(10);

    /// <summary>How long a command that is not a move may take to be answered.</summary>
    public TimeSpan CommandTimeout { get; init; } = TimeSpan.FromMilliseconds(500);

    /// <summary>A move's timeout is its trapezoid duration times this factor plus <see cref="MoveTimeoutMargin"/>.</summary>
    public double MoveTimeoutFactor { get; init; } = 1.5;

    public TimeSpan MoveTimeoutMargin { get; init; } = TimeSpan.FromSeconds(1);

    /// <summary>Renumber takes about half a second; nothing else is sent meanwhile.</summary>
    public TimeSpan RenumberTimeout { get; init; } = TimeSpan.FromSeconds(2);

    /// <summary>After a broadcast, replies are collected until the line has been quiet this long.</summary>
    public TimeSpan BroadcastQuietPeriod { get; init; } = TimeSpan.FromMilliseconds(100);

    /// <summary>After garbage or a timeout, wait out the partial-frame gap and confirm the line with Echo Data.</summary>
    public bool ResynchroniseAfterFaults { get; init; } = true;
}
