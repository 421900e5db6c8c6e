using System.Text.Json.Serialization;
using LaserEngrave.Core.Geometry;

namespace LaserEngrave.Simulator.Timing;

/// <summary>A delay of <see cref="MeanMs"/> ± <see cref="SpreadMs"/> milliseconds, drawn uniformly.</summary>
/// <param name="MeanMs">The mean delay, ms.</param>
/// <param name="SpreadMs">Half the width of the uniform spread, ms (0: always the mean).</param>
public readonly record struct Jitter([property: JsonPropertyName("meanMs")] double MeanMs, [property: JsonPropertyName("spreadMs")] double SpreadMs)
{
    /// <summary>No delay at all.</summary>
    public static Jitter None => default;

    /// <summary>One draw, in seconds, never below zero.</summary>
    public double SampleSeconds(Random random)
    {
        ArgumentNullException.ThrowIfNull(random);
        var ms = SpreadMs > 0 ? MeanMs + (((random.NextDouble() * 2) - 1) * SpreadMs) : MeanMs;
        return Units.MsToSeconds(Math.Max(0, ms));
    }

    /// <summary>The same jitter with its spread multiplied by <paramref name="factor"/>.</summary>
    public Jitter WithSpreadScaled(double factor) => this with { SpreadMs = SpreadMs * factor };

    public override string ToString() => FormattableString.Invariant($"{MeanMs} ± {SpreadMs} ms");
}
