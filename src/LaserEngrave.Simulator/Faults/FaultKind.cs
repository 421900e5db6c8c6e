namespace LaserEngrave.Simulator.Faults;

/// <summary>What an injected fault does.</summary>
public enum FaultKind
{
    /// <summary>A reply is not sent (the command still runs).</summary>
    DropReply,

    /// <summary>One byte of a reply is inverted.</summary>
    Corrupt,

    /// <summary>A reply leaves later than it should.</summary>
    Delay,

    /// <summary>A command is refused with an error reply instead of being carried out.</summary>
    Error,

    /// <summary>The device stops listening and answering, for good.</summary>
    Silent,

    /// <summary>The simulator closes its end of the link.</summary>
    Disconnect,

    /// <summary>The gate carries out commands but no longer acknowledges them.</summary>
    NoAck,
}

/// <summary>Which device a fault applies to.</summary>
public enum FaultTarget
{
    /// <summary>The Zaber chain (optionally one device of it).</summary>
    Stage,

    /// <summary>The laser gate.</summary>
    Gate,
}
