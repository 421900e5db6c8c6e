using System.Globalization;
using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Planning;

namespace LaserEngrave.Core.Jobs;

/// <summary>
/// What this computer can hold with this gate: the one rule for the fastest burn speed a host-timed run's edges keep
/// within the profile's edge tolerance, said before anything moves (the command line, the app, the API, preflight).
/// </summary>
/// <remarks>
/// A switching the host times itself lands as late as the host wakes: at v mm/s a lateness of t ms moves the edge v t µm,
/// and past the tolerance the run stops as a timing doubt (issue 34: the 10 x 10 sweep failed at 3.6-4 mm/s 25 minutes
/// in). So with a frequency-only gate, or a counting gate whose CAPS? does not list AFTER, the fastest speed is the
/// tolerance over the profile's <see cref="LatencyProfile.HostLatenessMs"/>. A gate that times its switch-ons itself
/// (scheduled bursts) takes the host's lateness out of the edge as long as the lead time covers it
/// (<see cref="TimedSwitching.PlannedSlackSeconds"/>); what remains, the adapter's delivery spread of that one line, the
/// guards cover at any speed (it narrows the lines, it does not stop the run), so such a gate holds every speed the stage runs.
/// </remarks>
public static class SpeedHold
{
    /// <summary>The fastest burn speed this computer holds with this gate, mm/s; +∞ when its lateness does not limit it.</summary>
    /// <param name="profile">The machine profile: its edge tolerance and the host's measured lateness.</param>
    /// <param name="scheduled">Whether the gate times its switch-ons (a counting gate whose CAPS? lists AFTER).</param>
    public static double FastestMmPerS(MachineProfile profile, bool scheduled)
    {
        ArgumentNullException.ThrowIfNull(profile);
        var lateness = profile.Latency.HostLatenessMs;
        if (scheduled && profile.Gate.CountsBursts && Units.MsToSeconds(lateness) <= TimedSwitching.PlannedSlackSeconds)
        {
            return double.PositiveInfinity;
        }

        return lateness <= 0 ? double.PositiveInfinity : profile.EdgeToleranceUm / lateness;
    }

    /// <summary>Null when a host-timed run at <paramref name="speedMmPerS"/> holds its edges; else the sentence that refuses it, with the fastest speed it holds.</summary>
    public static string? Problem(double speedMmPerS, MachineProfile profile, bool scheduled) =>
        Rule(speedMmPerS, profile, scheduled) is { } rule ? $"burn speed {N(speedMmPerS)} mm/s is {rule}" : null;

    /// <summary><see cref="Problem"/> without the speed it names: the rule a field's message puts after "burn speed 4 mm/s: ".</summary>
    public static string? Rule(double speedMmPerS, MachineProfile profile, bool scheduled)
    {
        var fastest = FastestMmPerS(profile, scheduled);
        return speedMmPerS <= fastest ? null : $"faster than this computer can hold with this gate: {Reason(speedMmPerS, profile)}; the fastest it holds is {N(Floor(fastest))} mm/s{Instead}";
    }

    // What a gate that times its switch-ons would change, said where a host-timed speed is refused.
    internal const string Instead = " (a gate that times its switch-ons, CAPS? listing AFTER, holds any)";

    internal static string Reason(double speed, MachineProfile profile)
    {
        var lateness = profile.Latency.HostLatenessMs;
        return $"it wakes up to {N(lateness)} ms late (the profile's latency.hostLatenessMs), {N(Math.Round(speed * lateness, 2))} µm at {N(speed)} mm/s, past the edge tolerance of {N(profile.EdgeToleranceUm)} µm";
    }

    // Rounded down to 0.01 mm/s, so that the speed named is one that holds.
    internal static double Floor(double mmPerS) => Math.Floor((mmPerS * 100) + 1e-9) / 100;

    internal static string N(double value) => value.ToString("0.###", CultureInfo.InvariantCulture);
}
