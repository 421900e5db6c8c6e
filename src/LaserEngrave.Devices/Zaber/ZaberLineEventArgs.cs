namespace LaserEngrave.Devices.Zaber;

/// <summary>Something the connection noticed about the line itself (noise, stale replies, resynchronisation).</summary>
public sealed class ZaberLineEventArgs(ZaberLineEvent kind, string message) : EventArgs
{
    public ZaberLineEvent Kind { get; } = kind;

    /// <summary>One line naming the port and what happened.</summary>
    public string Message { get; } = message;
}

/// <summary>Kinds of <see cref="ZaberLineEventArgs"/>.</summary>
public enum ZaberLineEvent
{
    /// <summary>An unfinished frame went quiet for longer than the partial-frame timeout and was dropped.</summary>
    PartialFrameDropped,

    /// <summary>Six bytes that cannot be a reply (unknown device or command); the line was discarded until quiet.</summary>
    GarbageDropped,

    /// <summary>A well-formed reply that no request is waiting for (for example one that arrived after its timeout).</summary>
    UnmatchedReply,

    /// <summary>The line was quiet and a device echoed Echo Data: frames are aligned again.</summary>
    Resynchronised,

    /// <summary>Echo Data was not answered after resynchronising.</summary>
    ResynchroniseFailed,
}
