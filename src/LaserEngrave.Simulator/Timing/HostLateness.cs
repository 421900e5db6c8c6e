using System.Text.Json.Serialization;
using LaserEngrave.Core.Geometry;

namespace LaserEngrave.Simulator.Timing;

/// <summary>
/// How late a computer busy with other work wakes the host from a timed wait: usually up to <see cref="TypicalMs"/>
/// (uniform), and with probability <see cref="TailProbability"/> anywhere up to <see cref="TailMs"/> (the tails an
/// antivirus scan or a second busy process give a Windows or Linux PC). Seeded: the same seed, the same lateness.
/// </summary>
/// <param name="TypicalMs">The usual lateness, 0 up to this, ms.</param>
/// <param name="TailProbability">How often a wait ends in the tail instead, 0..1.</param>
/// <param name="TailMs">How late a wait in the tail ends at most, ms.</param>
public readonly record struct HostLateness(
    [property: JsonPropertyName("typicalMs")] double TypicalMs,
    [property: JsonPropertyName("tailProbability")] double TailProbability,
    [property: JsonPropertyName("tailMs")] double TailMs)
{
    /// <summary>A host that wakes exactly on time (the library's default, for tests of the protocol alone).</summary>
    public static HostLateness None => default;

    /// <summary>
    /// A lab PC with other work on it (the front ends' default, <see cref="SimulatorOptions.FrontEnd"/>): up to 0.5 ms late, one wait in a hundred up to 5 ms (the ports bench's busy loops
    /// gave 2 ms typical and tails of 6-14 ms: <c>"hostLateness"</c> raises it).
    /// </summary>
    public static HostLateness Realistic => new(0.5, 0.01, 5);

    /// <summary>True when the host is never late.</summary>
    public bool IsNone => TypicalMs <= 0 && (TailProbability <= 0 || TailMs <= 0);

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

    public override string ToString() => FormattableString.Invariant($"up to {TypicalMs} ms, {TailProbability:P1} up to {TailMs} ms");
}
