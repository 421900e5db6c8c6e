using LaserEngrave.Core.Geometry;

namespace LaserEngrave.Devices.Machine;

/// <summary>What `machine latency` measured: the round trips to each axis and to the gate, and the profile's latency section they give.</summary>
/// <param name="X">Echo Data round trips to the X axis.</param>
/// <param name="Y">Echo Data round trips to the Y axis.</param>
/// <param name="Gate">Keepalive round trips to the laser gate.</param>
/// <param name="Host">How late this computer woke from timed waits over the probe; null when not measured (the profile's kept).</param>
public sealed record LatencyMeasurement(RoundTrips X, RoundTrips Y, RoundTrips Gate, HostWaits? Host = null)
{
    /// <summary>Both axes' round trips together: one link, one adapter.</summary>
    public RoundTrips Stage => X.With(Y, "stage");

    /// <summary>
    /// The latency section these round trips give, keeping <paramref name="kept"/>'s gate processing time and spread.
    /// </summary>
    /// <remarks>
    /// A round trip is the wire time plus the adapter's latency twice (the command out, the reply back, each drawn afresh),
    /// plus on the gate its processing, which no round trip can tell apart from the adapter's: it is taken from the profile
    /// as it stands. So the one-way latency is (mean round trip - wire - processing) / 2. The half-width h of each
    /// one-way draw is the larger of two. From the round trips' variance, as uniform draws give it: s² = 2 h² / 3 (+ hp² / 3
    /// for the gate's processing of half-width hp); the range of a few hundred round trips alone would understate a
    /// uniform spread, since two or three draws rarely reach their extremes together (about 0.45 of 0.5 ms on the
    /// simulator). And from the round trip furthest from the mean, |d| &lt;= 2 h + hp: on a busy computer the delays have
    /// tails that the variance understates (a few round trips 5 to 15 ms late among hundreds within 2 ms), and every check
    /// the host makes against the profile's spread must allow what was seen.
    /// </remarks>
    public LatencyProfile ToProfile(LatencyProfile kept)
    {
        ArgumentNullException.ThrowIfNull(kept);
        var stage = Stage;
        return kept with
        {
            StageMs = OneWay(stage.MeanMs - stage.WireMs),
            StageJitterMs = HalfWidth(stage, 0),
            GateMs = OneWay(Gate.MeanMs - Gate.WireMs - kept.GateProcessingMs),
            GateJitterMs = HalfWidth(Gate, kept.GateProcessingJitterMs),
            HostLatenessMs = Host?.Percentile98Ms ?? kept.HostLatenessMs,
            HostLatenessTailMs = Host is { } host ? Math.Max(host.MaxMs, host.Percentile98Ms) : kept.HostLatenessTailMs,
        };
    }

    // Never below 0: a round trip shorter than its wire time (a clock's resolution, a processing time set too high) means no latency to plan for.
    private static double OneWay(double roundTripMs) => Math.Max(0, roundTripMs / 2);

    // s² = 2 h² / 3 + hp² / 3 solved for h, or |d| <= 2 h + hp for the furthest round trip, whichever is larger.
    private static double HalfWidth(RoundTrips trips, double processingHalfWidthMs)
    {
        var s = trips.StdDevMs;
        var fromVariance = Math.Sqrt(Math.Max(0, (3 * s * s) - (processingHalfWidthMs * processingHalfWidthMs)) / 2);
        var furthest = Math.Max(trips.MaxMs - trips.MeanMs, trips.MeanMs - trips.MinMs);
        return Math.Max(fromVariance, Math.Max(0, furthest - processingHalfWidthMs) / 2);
    }
}

/// <summary>How late this computer woke from timed waits (each as a timed switching waits), ms beyond the time asked.</summary>
/// <param name="Count">Waits timed.</param>
/// <param name="Percentile98Ms">
/// The lateness 98 % of the waits stayed within: the profile's latency.hostLatenessMs. Not the 99th: a lab PC late in 1 %
/// of its waits (the twin's realistic host) puts that one in its tail every other probe (0.99 ms against 0.50 on seed 2).
/// </param>
/// <param name="MaxMs">The latest wake-up seen: the profile's latency.hostLatenessTailMs.</param>
public sealed record HostWaits(int Count, double Percentile98Ms, double MaxMs)
{
    /// <summary>The figures of <paramref name="latenessMs"/>, each wait's lateness (negative, a wait ended early, counts as 0).</summary>
    public static HostWaits Of(IReadOnlyList<double> latenessMs)
    {
        ArgumentNullException.ThrowIfNull(latenessMs);
        if (latenessMs.Count == 0)
        {
            throw new ArgumentException("no wait was timed", nameof(latenessMs));
        }

        var sorted = latenessMs.Select(ms => Math.Max(0, ms)).Order().ToArray();

        // The nearest-rank 98th percentile: of 1000 waits the 980th, so twenty may lie beyond it.
        var rank = (int)Math.Ceiling(0.98 * sorted.Length) - 1;
        return new HostWaits(sorted.Length, sorted[Math.Clamp(rank, 0, sorted.Length - 1)], sorted[^1]);
    }
}
