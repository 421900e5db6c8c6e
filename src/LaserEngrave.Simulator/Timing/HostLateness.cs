using System.Text.Json.Serialization;
using LaserEngrave.Core.Geometry;

namespace LaserEngrave.Simulator.Timing;

/// <summary>
/// How late a computer busy with other work is: it wakes the host from a timed wait usually up to <see cref="TypicalMs"/>
/// late (uniform), and with probability <see cref="TailProbability"/> anywhere up to <see cref="TailMs"/> (the tails an
/// antivirus scan or a second busy process give a Windows or Linux PC); rarely it stalls between stamping a write and
/// the write itself (<see cref="StallProbability"/>), and its reader is rarely late to read what arrived
/// (<see cref="LateReadProbability"/>). Seeded: the same seed, the same lateness.
/// </summary>
/// <param name="TypicalMs">The usual lateness, 0 up to this, ms.</param>
/// <param name="TailProbability">How often a wait ends in the tail instead, 0..1.</param>
/// <param name="TailMs">How late a wait in the tail ends at most, ms.</param>
public readonly record struct HostLateness(
    [property: JsonPropertyName("typicalMs")] double TypicalMs,
    [property: JsonPropertyName("tailProbability")] double TailProbability,
    [property: JsonPropertyName("tailMs")] double TailMs)
{
    /// <summary>The shortest stall or late read drawn, ms (what is shorter is the typical lateness).</summary>
    public const double ShortestStallMs = 5;

    /// <summary>
    /// How often a write of the host is held up between the moment it was stamped (the time its line was timed from) and
    /// the moment the operating system takes its bytes, 0..1: another process scheduled in, a page fault. The bytes
    /// leave that much later and the write returns that much later (docs/simulator.md, "A loaded computer").
    /// </summary>
    [JsonPropertyName("stallProbability")]
    public double StallProbability { get; init; }

    /// <summary>How long such a stall lasts at most, ms (from <see cref="ShortestStallMs"/>, uniform).</summary>
    [JsonPropertyName("stallMs")]
    public double StallMs { get; init; }

    /// <summary>How often the host's reader is late to read bytes that have arrived, 0..1 (they keep their arrival time).</summary>
    [JsonPropertyName("lateReadProbability")]
    public double LateReadProbability { get; init; }

    /// <summary>How late such a read is at most, ms (from <see cref="ShortestStallMs"/>, uniform).</summary>
    [JsonPropertyName("lateReadMs")]
    public double LateReadMs { get; init; }

    /// <summary>A host that wakes exactly on time, never stalls and reads at once (the library's default, for tests of the protocol alone).</summary>
    public static HostLateness None => default;

    /// <summary>
    /// A lab PC with other work on it (the front ends' default, <see cref="SimulatorOptions.FrontEnd"/>): up to 0.5 ms late,
    /// one wait in a hundred up to 5 ms; one write in 2,000 stalled 5-30 ms before it leaves, one read in 2,000 up to 60 ms
    /// late (the ports bench's busy loops gave 2 ms typical, tails of 6-14 ms, writes stalled 9-20 ms and replies read
    /// 33-100 ms late: <c>"hostLateness"</c> raises it).
    /// </summary>
    public static HostLateness Realistic => new(0.5, 0.01, 5) { StallProbability = 0.0005, StallMs = 30, LateReadProbability = 0.0005, LateReadMs = 60 };

    /// <summary>True when the host is never late.</summary>
    public bool IsNone => WakesOnTime && !Stalls && !ReadsLate;

    /// <summary>True when the host wakes from its timed waits on time.</summary>
    public bool WakesOnTime => TypicalMs <= 0 && (TailProbability <= 0 || TailMs <= 0);

    /// <summary>True when some writes stall between their stamp and the write.</summary>
    public bool Stalls => StallProbability > 0 && StallMs > 0;

    /// <summary>True when the reader is sometimes late.</summary>
    public bool ReadsLate => LateReadProbability > 0 && LateReadMs > 0;

    /// <summary>One wait's lateness, seconds.</summary>
    public double SampleSeconds(Random random)
    {
        ArgumentNullException.ThrowIfNull(random);
        var typical = Math.Max(0, TypicalMs);
        var ms = random.NextDouble() < TailProbability
            ? typical + (random.NextDouble() * Math.Max(0, TailMs - typical))
            : random.NextDouble() * typical;
        return Units.MsToSeconds(ms);
    }

    /// <summary>One write's stall between its stamp and the write, seconds (0: none).</summary>
    public double StallSeconds(Random random) => Rare(random, StallProbability, StallMs);

    /// <summary>How late one read is, seconds (0: read at once).</summary>
    public double LateReadSeconds(Random random) => Rare(random, LateReadProbability, LateReadMs);

    public override string ToString() => FormattableString.Invariant(
        $"up to {TypicalMs} ms, {TailProbability:P1} up to {TailMs} ms") + (Stalls ? FormattableString.Invariant($", {StallProbability:P2} of writes stalled up to {StallMs} ms") : string.Empty)
        + (ReadsLate ? FormattableString.Invariant($", {LateReadProbability:P2} of reads up to {LateReadMs} ms late") : string.Empty);

    private static double Rare(Random random, double probability, double maxMs)
    {
        ArgumentNullException.ThrowIfNull(random);
        if (probability <= 0 || maxMs <= 0 || random.NextDouble() >= probability)
        {
            return 0;
        }

        var least = Math.Min(ShortestStallMs, maxMs);
        return Units.MsToSeconds(least + (random.NextDouble() * (maxMs - least)));
    }
}
