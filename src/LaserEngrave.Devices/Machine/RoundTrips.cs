namespace LaserEngrave.Devices.Machine;

/// <summary>The round trips measured to one device: how many, their least, mean and greatest time, and the wire time within each.</summary>
/// <param name="Device">What answered, as messages name it ("X axis (device 1)", "laser gate").</param>
/// <param name="Count">Exchanges timed.</param>
/// <param name="MinMs">Shortest round trip, ms.</param>
/// <param name="MeanMs">Mean round trip, ms.</param>
/// <param name="MaxMs">Longest round trip, ms.</param>
/// <param name="StdDevMs">Standard deviation of the round trips, ms (0 for a single one).</param>
/// <param name="WireMs">The part of each round trip the bytes spend on the wire (bytes x 10 bits / baud, both ways), ms.</param>
public sealed record RoundTrips(string Device, int Count, double MinMs, double MeanMs, double MaxMs, double StdDevMs, double WireMs)
{
    /// <summary>Half the range of the round trips, ms: the mean ± this holds every exchange.</summary>
    public double SpreadMs => (MaxMs - MinMs) / 2;

    /// <summary>The figures of <paramref name="roundTripsMs"/>, each a round trip in ms.</summary>
    public static RoundTrips Of(string device, IReadOnlyCollection<double> roundTripsMs, double wireMs)
    {
        ArgumentNullException.ThrowIfNull(roundTripsMs);
        if (roundTripsMs.Count == 0)
        {
            throw new ArgumentException($"{device}: no round trip to summarise", nameof(roundTripsMs));
        }

        var mean = roundTripsMs.Average();
        var n = roundTripsMs.Count;
        var variance = n < 2 ? 0 : roundTripsMs.Sum(t => (t - mean) * (t - mean)) / (n - 1);
        return new RoundTrips(device, n, roundTripsMs.Min(), mean, roundTripsMs.Max(), Math.Sqrt(variance), wireMs);
    }

    /// <summary>Both sets of round trips taken as one (the two axes share one link and its adapter).</summary>
    public RoundTrips With(RoundTrips other, string device)
    {
        ArgumentNullException.ThrowIfNull(other);
        var count = Count + other.Count;
        var mean = ((MeanMs * Count) + (other.MeanMs * other.Count)) / count;

        // Pooled: each set's squared deviations about the common mean.
        var squares = Squares(this, mean) + Squares(other, mean);
        var std = count < 2 ? 0 : Math.Sqrt(squares / (count - 1));
        return new RoundTrips(device, count, Math.Min(MinMs, other.MinMs), mean, Math.Max(MaxMs, other.MaxMs), std, WireMs);
    }

    private static double Squares(RoundTrips trips, double mean) =>
        (Math.Max(0, trips.Count - 1) * trips.StdDevMs * trips.StdDevMs) + (trips.Count * (trips.MeanMs - mean) * (trips.MeanMs - mean));
}
