using System.Numerics;
using LaserEngrave.Core.Imaging;
using LaserEngrave.Core.Logging;
using LaserEngrave.Simulator.Burn;
using LaserEngrave.Simulator.Motion;

namespace LaserEngrave.Simulator.Replay;

/// <summary>
/// What a replay cannot know about a recorded run, in the burn's own terms: how far each switching of the laser could lie
/// from where the replay put it, and which pixels could have come out otherwise, within the bands the recording leaves
/// open (<see cref="RecordedDelays"/>). Never counted as pulses on white: a pulse the estimate puts on white is one, a
/// pixel that only an end of a band burns or spares is uncertain.
/// </summary>
/// <param name="EdgesWithinUm">Every switching lies within this distance of where the replay put it, µm.</param>
/// <param name="Switchings">The laser's switchings on and off that the three replays share.</param>
/// <param name="UncertainEdges">Switchings whose band is wider than <see cref="EdgeResolutionUm"/>.</param>
/// <param name="UncertainPixels">Pixels burned at one end of the bands and not at the estimate or the other end; null for a drawing.</param>
/// <param name="PulsesOnWhite">Pulses on white (or off the job) at the estimate and at the two ends: the least and the most.</param>
/// <param name="UnmatchedSwitchings">Switchings made at one end of the bands and not at the other (0: the same laser switchings at all three).</param>
/// <param name="Edges">Each switching with its band, in the order the laser switched, the widest first when more than <see cref="MaxEdgesListed"/> are uncertain.</param>
/// <param name="Stage">What the stage link's round trips showed.</param>
/// <param name="Gate">What the gate link's round trips showed.</param>
/// <param name="Positions">How the replay's stage agreed with the positions the run's stages reported.</param>
public sealed record ReplayUncertainty(
    double EdgesWithinUm,
    int Switchings,
    int UncertainEdges,
    long? UncertainPixels,
    PulseCountBounds PulsesOnWhite,
    int UnmatchedSwitchings,
    IReadOnlyList<EdgeBand> Edges,
    LinkDelays Stage,
    LinkDelays Gate,
    PositionAgreement Positions)
{
    /// <summary>A band narrower than this is no band (the recording's times are to 0.1 µs).</summary>
    public const double ResolutionSeconds = 1e-6;

    /// <summary>A switching this close at both ends counts as placed, µm.</summary>
    public const double EdgeResolutionUm = 0.05;

    /// <summary>The most edges <see cref="Edges"/> lists.</summary>
    public const int MaxEdgesListed = 200;

    /// <summary>One line: "edges placed within ±x µm; N pixels uncertain", and what the host read late.</summary>
    public string Summary()
    {
        var pixels = UncertainPixels is { } n ? FormattableString.Invariant($"; {n} pixel{(n == 1 ? string.Empty : "s")} uncertain") : string.Empty;
        var late = Stage.RepliesReadLate + Gate.RepliesReadLate;
        var host = late == 0
            ? "no reply read late"
            : FormattableString.Invariant($"{late} repl{(late == 1 ? "y" : "ies")} read late by the host (up to {Math.Max(Stage.LongestReadLateSeconds, Gate.LongestReadLateSeconds) * 1000:0.#} ms), taken as the host's, not the delivery's");
        var onWhite = PulsesOnWhite.Least == PulsesOnWhite.Most ? string.Empty : FormattableString.Invariant($"; pulses on white {PulsesOnWhite.Least}..{PulsesOnWhite.Most} within the bands");
        var positions = Positions.Reported == 0
            ? "no position reported"
            : FormattableString.Invariant($"{Positions.Reported} reported positions, {Positions.Corrected} motion writes moved to them, the stage within {Positions.WorstOffUm:0.##} µm of each");
        return FormattableString.Invariant($"edges placed within ±{EdgesWithinUm:0.##} µm ({UncertainEdges} of {Switchings} switchings uncertain){pixels}{onWhite}; {host}; {positions}");
    }

    internal static ReplayUncertainty Compare(ReplayRun estimate, ReplayRun gateEarly, ReplayRun gateLate, RecordedDelays delays, PositionAgreement positions)
    {
        var count = Math.Min(estimate.Switches.Count, Math.Min(gateEarly.Switches.Count, gateLate.Switches.Count));
        var edges = new List<EdgeBand>(count);
        for (var i = 0; i < count; i++)
        {
            var s = estimate.Switches[i];
            edges.Add(new EdgeBand(s.AtSeconds, s.On, s.XUm, s.YUm, Distance(s, gateEarly.Switches[i]), Distance(s, gateLate.Switches[i])));
        }

        var uncertain = edges.Where(e => e.WidthUm > EdgeResolutionUm).ToList();
        var listed = uncertain.Count > MaxEdgesListed ? [.. uncertain.OrderByDescending(e => e.WidthUm).Take(MaxEdgesListed)] : uncertain;
        var onWhite = new[] { estimate, gateEarly, gateLate }.Select(r => r.Simulation.LaserOnTravelCount).ToList();
        return new ReplayUncertainty(
            edges.Count == 0 ? 0 : edges.Max(e => e.WidthUm),
            edges.Count,
            uncertain.Count,
            estimate.Burn is { } burn ? Differing(burn.Burned, gateEarly.Burn!.Burned, gateLate.Burn!.Burned) : null,
            new PulseCountBounds(onWhite.Min(), onWhite.Max()),
            Math.Max(estimate.Switches.Count, Math.Max(gateEarly.Switches.Count, gateLate.Switches.Count)) - count,
            listed,
            delays.Stage,
            delays.Gate,
            positions);
    }

    private static double Distance(LaserSwitch a, LaserSwitch b) => Math.Sqrt(((a.XUm - b.XUm) * (a.XUm - b.XUm)) + ((a.YUm - b.YUm) * (a.YUm - b.YUm)));

    // Pixels not burned alike by all three.
    private static long Differing(BitMask estimate, BitMask early, BitMask late)
    {
        long count = 0;
        for (var y = 0; y < estimate.Height; y++)
        {
            var a = estimate.ReadRow(y);
            var b = early.ReadRow(y);
            var c = late.ReadRow(y);
            for (var w = 0; w < a.Length; w++)
            {
                count += BitOperations.PopCount((a[w] ^ b[w]) | (a[w] ^ c[w]));
            }
        }

        return count;
    }
}

/// <summary>One switching of the laser as the replay placed it, and how far it lies at each end of the bands.</summary>
/// <param name="AtSeconds">When, on the replay's clock (the recording's, from its start).</param>
/// <param name="On">Switched on (a first pulse) or off.</param>
/// <param name="XUm">Where the stage stood, X, µm.</param>
/// <param name="YUm">Y, µm.</param>
/// <param name="GateEarlyUm">How far from there it lies with the gate's writes at their earliest and the stage's at their latest, µm.</param>
/// <param name="GateLateUm">The other way round, µm.</param>
public sealed record EdgeBand(double AtSeconds, bool On, double XUm, double YUm, double GateEarlyUm, double GateLateUm)
{
    /// <summary>The band's half width: the farther of its two ends, µm.</summary>
    public double WidthUm => Math.Max(GateEarlyUm, GateLateUm);
}

/// <summary>The least and the most of a count of pulses within the bands.</summary>
public sealed record PulseCountBounds(long Least, long Most);

/// <summary>One switching of the laser in a replay: when, on or off, where the stage stood (µm).</summary>
internal sealed record LaserSwitch(double AtSeconds, bool On, double XUm, double YUm);

/// <summary>One replay's figures, burn report (an image's) and laser switchings; its axes by device number and the twin's clock at the recording's start.</summary>
internal sealed record ReplayRun(RunSimulation Simulation, BurnReport? Burn, IReadOnlyList<LaserSwitch> Switches, IReadOnlyDictionary<byte, AxisTrajectory> Axes, double StartSeconds);
