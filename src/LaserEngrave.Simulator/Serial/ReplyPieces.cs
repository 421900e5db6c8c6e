using System.Text.Json.Serialization;

namespace LaserEngrave.Simulator.Serial;

/// <summary>
/// How a USB-serial adapter delivers a device's reply to the host: with probability <see cref="Probability"/> in two
/// pieces, cut at a random byte, the first <see cref="GapMs"/> before the last (which arrives when it would have whole).
/// Real adapters do this (the FTDI latency timer); the host must not take the gap for a broken frame.
/// </summary>
/// <param name="Probability">How often a reply comes in two pieces, 0..1.</param>
/// <param name="GapMs">How far apart the pieces arrive, ms.</param>
public readonly record struct ReplyPieces(
    [property: JsonPropertyName("probability")] double Probability,
    [property: JsonPropertyName("gapMs")] double GapMs)
{
    /// <summary>Every reply whole (the library's default).</summary>
    public static ReplyPieces None => default;

    /// <summary>The front ends' default: one reply in ten in two pieces 3 ms apart, as a USB adapter on a loaded PC delivered them.</summary>
    public static ReplyPieces Realistic => new(0.1, 3);

    /// <summary>True when every reply arrives whole.</summary>
    public bool IsNone => Probability <= 0 || GapMs <= 0;

    /// <summary>Where to cut a reply of <paramref name="length"/> bytes (null: whole), drawn from <paramref name="random"/>.</summary>
    public int? CutAt(int length, Random random)
    {
        ArgumentNullException.ThrowIfNull(random);
        if (IsNone || length < 2 || random.NextDouble() >= Probability)
        {
            return null;
        }

        return 1 + random.Next(length - 1);
    }

    public override string ToString() => FormattableString.Invariant($"{Probability:P0} of replies in two pieces {GapMs} ms apart");
}
