using LaserEngrave.Core.Jobs;
using LaserEngrave.Core.Planning;

namespace LaserEngrave.Devices.Execution;

/// <summary>How a run starts and how hard it tries when things go wrong.</summary>
public sealed record RunOptions
{
    public static RunOptions Default { get; } = new();

    /// <summary>Home both axes in preflight even when they are homed already.</summary>
    public bool Home { get; init; }

    /// <summary>An axis with auto-reply disabled (Device Mode bit 0) never confirms a move: clear the bit (true) or refuse (false).</summary>
    public bool FixAutoReply { get; init; } = true;

    /// <summary>Continue a stopped run from here: the first burn run not completed (null = from the start).</summary>
    public RunStopPoint? ResumeFrom { get; init; }

    /// <summary>Keepalive period as a fraction of the gate's watchdog time (the profile's <c>gate.watchdogMs</c>).</summary>
    public double KeepAliveFraction { get; init; } = 0.25;

    /// <summary>
    /// How many times the profile's latency spread (its jitter) the run assumes, at least 1: its edge guards and its
    /// position checks widen by it. A session that goes on after a check found the stage further from its plan than the
    /// profile allows passes on what that run found (<see cref="RunResult.LatencyScale"/>), so that the laser keeps off
    /// the white with the spread that was seen.
    /// </summary>
    public double LatencyScale { get; init; } = 1;

    /// <summary>
    /// The person accepts a gate without a watchdog (a frequency-only profile): when this computer hangs with the laser on,
    /// only the interlock or the key switch stops it (<see cref="Core.Geometry.LaserGateProfile.NoWatchdogSentence"/>).
    /// Without it preflight refuses such a run before anything is sent; the run log keeps that it was accepted.
    /// </summary>
    public bool AcceptNoWatchdog { get; init; }

    /// <summary>How late past its expected arrival a stage reply may come before the run counts the stage as stalled, ms.</summary>
    public double StallMarginMs { get; init; } = 20;
}
