using LaserEngrave.Simulator.Timing;

namespace LaserEngrave.Simulator.Serial;

/// <summary>The delays of one link besides the wire: the USB-serial adapter each way and the device's processing, drawn from one seeded source.</summary>
/// <remarks>Replies in pieces draw from a source of their own, so that the latencies stay what they were without them.</remarks>
internal sealed class LinkLatency(Jitter adapter, Jitter processing, Random random)
{
    private ReplyPieces _pieces;
    private Random? _piecesRandom;

    /// <summary>Delivers replies in pieces, drawn from <paramref name="piecesRandom"/>.</summary>
    public LinkLatency WithPieces(ReplyPieces pieces, Random piecesRandom)
    {
        _pieces = pieces;
        _piecesRandom = piecesRandom;
        return this;
    }

    /// <summary>The adapter's latency for one write of the host.</summary>
    public double ToDeviceSeconds() => adapter.SampleSeconds(random);

    /// <summary>The adapter's latency for one reply of the device.</summary>
    public double ToHostSeconds() => adapter.SampleSeconds(random);

    /// <summary>From a command's last byte to its effect (and its reply).</summary>
    public double ProcessingSeconds() => processing.SampleSeconds(random);

    /// <summary>Where a reply of <paramref name="length"/> bytes is cut, and how far apart its pieces arrive (s); null: whole.</summary>
    public (int At, double GapSeconds)? Cut(int length) =>
        _piecesRandom is { } r && _pieces.CutAt(length, r) is { } at ? (at, _pieces.GapMs / 1000) : null;
}
