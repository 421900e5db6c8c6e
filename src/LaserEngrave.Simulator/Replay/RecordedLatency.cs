using LaserEngrave.Core.Geometry;
using LaserEngrave.Wire.Serial;
using LaserEngrave.Wire.Zaber;

namespace LaserEngrave.Simulator.Replay;

/// <summary>
/// How late each recorded write reached its device, taken from what the recording shows: each round trip from a write to
/// its reply's arrival, less the wire's time both ways, the bytes still ahead of it on the wire and the device's own
/// processing, is the adapter's delay out plus its delay back; the link's prompt round trips show how long one way takes
/// on that adapter, and what a round trip took beyond that was the host's (its reply read late), not the delivery's.
/// </summary>
/// <remarks>
/// <para>
/// A round trip cannot be split by the recording alone: a reply read 200 ms late by a stalled host and a write delivered
/// 200 ms late look the same from the host. Halving it (as the replay did until issue 34) made every host stall a late
/// delivery: a host stopped for 200 ms replayed with pulses on white that never happened. Here the link's round trips
/// say how fast its adapter is: the fastest shows its floor, and those not far beyond the usual (the lower quartile plus
/// two and a half times its distance from the fastest, at least 0.2 ms; a uniform spread each way stays within it) its
/// range one way, <c>[fastest / 2, slowest usual / 2]</c>.
/// A write whose round trip is within that range is estimated at half of it and can lie anywhere the range allows for
/// both ways; a longer one (a reply read late) and a write with no reply of its own (a Zaber move replies when it ends)
/// are estimated at the middle of the range and can lie anywhere in it. A delivery later than the adapter has shown it
/// can be is not excluded by the recording; the replay reports each band it leaves open in µm instead of guessing.
/// </para>
/// <para>
/// The twin's wire queues a write behind the bytes still going out, as the run's wire did, so the estimate is the
/// adapter's part only. Gate replies pair with the writes in order, Zaber replies by device and command; the gate's
/// processing of a line (a scheduled burst's wait excluded: it is answered when armed) is the twin's.
/// </para>
/// </remarks>
public static class RecordedLatency
{
    /// <summary>Round trips this much beyond the usual ones are the host's at the least (a reader late by less is within a USB adapter's spread).</summary>
    public const double UsualSpreadFloorSeconds = 0.0002;


    /// <summary>The one-way delay, seconds, of each event of <paramref name="events"/> that is a write (0 for the rest; 0 for every write on a link without one usable reply).</summary>
    /// <param name="profile">The machine (baud rates, the gate's line terminator).</param>
    /// <param name="events">The recording.</param>
    /// <param name="gateProcessingSeconds">The gate's own time from a command's last byte to its reply, seconds, for the command's bytes (the twin's, which the replay keeps).</param>
    public static double[] OneWaySeconds(MachineProfile profile, IReadOnlyList<WireEvent> events, Func<byte[], double> gateProcessingSeconds) =>
        Estimate(profile, events, gateProcessingSeconds).Seconds();

    /// <summary>Each write's delay with the band the recording leaves open, and what each link's round trips showed.</summary>
    /// <inheritdoc cref="OneWaySeconds" path="/param"/>
    public static RecordedDelays Estimate(MachineProfile profile, IReadOnlyList<WireEvent> events, Func<byte[], double> gateProcessingSeconds)
    {
        ArgumentNullException.ThrowIfNull(profile);
        ArgumentNullException.ThrowIfNull(events);
        ArgumentNullException.ThrowIfNull(gateProcessingSeconds);
        var roundTrips = new double?[events.Count];
        var rest = new double[events.Count];
        var positions = new List<RecordedPosition>();
        StageRoundTrips(profile, events, roundTrips, rest, positions);
        GateRoundTrips(profile, events, roundTrips, rest, gateProcessingSeconds);
        var result = new WriteDelay[events.Count];
        var stage = EstimateLink(events, true, profile.StageBaudRate, roundTrips, rest, result);
        var gate = EstimateLink(events, false, profile.Gate.BaudRate, roundTrips, rest, result);
        return new RecordedDelays(result, stage, gate) { Positions = positions };
    }

    private static LinkDelays EstimateLink(IReadOnlyList<WireEvent> events, bool stage, int baud, double?[] roundTrips, double[] rest, WriteDelay[] result)
    {
        var secondsPerByte = SerialLine.BitsPerByte / baud;
        var writes = Enumerable.Range(0, events.Count).Where(i => events[i].Write && events[i].Stage == stage && events[i].Layer is null).ToList();

        // The adapters' part of each round trip: what the wire's queue explains is taken out first. With the adapter's
        // delay the same for each write the queue does not depend on it, so it is measured as if there were none.
        var adapters = new Dictionary<int, double>();
        var wireFreeAt = double.NegativeInfinity;
        foreach (var i in writes)
        {
            var e = events[i];
            var queue = Math.Max(0, wireFreeAt - e.Seconds);
            if (roundTrips[i] is { } roundTrip)
            {
                adapters[i] = Math.Max(0, roundTrip - rest[i] - queue);
            }

            wireFreeAt = Math.Max(e.Seconds, wireFreeAt) + (e.Data.Length * secondsPerByte);
        }

        if (adapters.Count == 0)
        {
            return new LinkDelays(0, 0, 0, 0, 0);
        }

        var sorted = adapters.Values.Order().ToList();
        var fastest = sorted[0];
        // The lower quartile, not the median: a host that read half its replies late must not make them usual.
        var quartile = sorted[sorted.Count / 4];
        var usualUpTo = quartile + Math.Max(2.5 * (quartile - fastest), UsualSpreadFloorSeconds);
        var usual = sorted.Where(x => x <= usualUpTo).ToList();
        var slowest = usual[^1];

        // Half a round trip is the mean of two draws, which reaches its extremes seldom: n of them fall short of the
        // one-way range by about its width times sqrt(1 / 2n) at each end (a sum of two uniform draws), so the range is
        // widened by half as much again as that (a few round trips: a third of it and more; a QR's hundreds: 7 %).
        var shortfall = Math.Sqrt(1.0 / (2 * usual.Count));
        var widen = shortfall >= 0.4 ? (slowest - fastest) / 2 : 1.5 * (slowest - fastest) / 2 * shortfall / (1 - (2 * shortfall));
        var (low, high) = (Math.Max(0, (fastest / 2) - widen), (slowest / 2) + widen);
        var middle = new WriteDelay((low + high) / 2, low, high);
        var late = 0;
        var longestLate = 0.0;
        foreach (var i in writes)
        {
            if (adapters.TryGetValue(i, out var both) && both <= usualUpTo)
            {
                // Within the adapter's range: one way took between what the other way can leave of it.
                var earliest = Math.Max(low, both - high);
                var latest = Math.Min(high, both - low);
                result[i] = earliest <= latest ? new WriteDelay(Math.Clamp(both / 2, earliest, latest), earliest, latest) : new WriteDelay(both / 2, both / 2, both / 2);
                continue;
            }

            if (adapters.TryGetValue(i, out var longer))
            {
                // Longer than this adapter takes both ways: the rest was the host's (its reader late, or the whole host stopped).
                late++;
                longestLate = Math.Max(longestLate, longer - (2 * middle.Seconds));
            }

            result[i] = middle;
        }

        return new LinkDelays(adapters.Count, low, high, late, longestLate);
    }

    // Each Zaber write's round trip to its reply (a command that replies at once), and the wire's part of it.
    private static void StageRoundTrips(MachineProfile profile, IReadOnlyList<WireEvent> events, double?[] roundTrips, double[] rest, List<RecordedPosition> positions)
    {
        var wire = 2 * ZaberFrame.Length * SerialLine.BitsPerByte / profile.StageBaudRate;
        var pending = new List<(byte Device, byte Command, int Index)>();
        var bytes = new List<byte>();
        for (var i = 0; i < events.Count; i++)
        {
            var e = events[i];
            if (!e.Stage || e.Layer is not null)
            {
                continue;
            }

            if (e.Write)
            {
                for (var at = 0; at + ZaberFrame.Length <= e.Data.Length; at += ZaberFrame.Length)
                {
                    if ((ZaberCommand)e.Data[at + 1] is not (ZaberCommand.Home or ZaberCommand.MoveAbsolute or ZaberCommand.MoveRelative or ZaberCommand.Stop))
                    {
                        pending.Add((e.Data[at], e.Data[at + 1], i));
                    }
                }

                continue;
            }

            bytes.AddRange(e.Data);
            while (bytes.Count >= ZaberFrame.Length)
            {
                var (device, command) = (bytes[0], bytes[1]);
                var data = BitConverter.ToInt32([bytes[2], bytes[3], bytes[4], bytes[5]]);
                bytes.RemoveRange(0, ZaberFrame.Length);
                var match = pending.FindIndex(p => p.Device == device && p.Command == command);
                if (match < 0)
                {
                    continue;
                }

                var write = pending[match].Index;
                pending.RemoveAt(match);
                roundTrips[write] ??= e.Seconds - events[write].Seconds;
                rest[write] = wire;
                if ((ZaberCommand)command == ZaberCommand.ReturnCurrentPosition)
                {
                    positions.Add(new RecordedPosition(write, device, data));
                }
            }
        }
    }

    // Each gate command's round trip to its reply line (in order), and the wire's and the gate's processing part of it.
    private static void GateRoundTrips(MachineProfile profile, IReadOnlyList<WireEvent> events, double?[] roundTrips, double[] rest, Func<byte[], double> processingSeconds)
    {
        var terminator = (byte)profile.Gate.LineTerminator[^1];
        var secondsPerByte = SerialLine.BitsPerByte / profile.Gate.BaudRate;
        var pending = new Queue<int>();
        var line = 0;
        for (var i = 0; i < events.Count; i++)
        {
            var e = events[i];
            if (e.Stage || e.Layer is not null)
            {
                continue;
            }

            if (e.Write)
            {
                pending.Enqueue(i);
                continue;
            }

            foreach (var b in e.Data)
            {
                line++;
                if (b != terminator)
                {
                    continue;
                }

                if (pending.TryDequeue(out var write))
                {
                    roundTrips[write] = e.Seconds - events[write].Seconds;
                    rest[write] = ((events[write].Data.Length + line) * secondsPerByte) + processingSeconds(events[write].Data);
                }

                line = 0;
            }
        }
    }
}

/// <summary>One write's delay on its adapter before its bytes went out, seconds: the estimate, and the earliest and latest the recording leaves open.</summary>
public readonly record struct WriteDelay(double Seconds, double EarliestSeconds, double LatestSeconds);

/// <summary>What one link's round trips showed.</summary>
/// <param name="RoundTrips">Writes whose reply told their round trip.</param>
/// <param name="FastestSeconds">The adapter's quickest one way, seconds (half the fastest round trip's adapter part).</param>
/// <param name="SlowestSeconds">Its slowest usual one way, seconds.</param>
/// <param name="RepliesReadLate">Round trips longer than the adapter takes both ways: replies the host read late.</param>
/// <param name="LongestReadLateSeconds">The most the host read a reply late by, seconds.</param>
public sealed record LinkDelays(int RoundTrips, double FastestSeconds, double SlowestSeconds, int RepliesReadLate, double LongestReadLateSeconds);

/// <summary>A position a stage reported: the write of its query (an event's index), the device, the position in microsteps.</summary>
public sealed record RecordedPosition(int WriteIndex, byte Device, int Microsteps);

/// <summary>Each event's delay (<see cref="WriteDelay"/>; default for an event that is not a write), and what each link showed.</summary>
public sealed record RecordedDelays(IReadOnlyList<WriteDelay> Writes, LinkDelays Stage, LinkDelays Gate)
{
    /// <summary>Every position the stages reported to a Return Current Position, in the order they were asked.</summary>
    public IReadOnlyList<RecordedPosition> Positions { get; init; } = [];

    /// <summary>Each event's estimated delay, seconds.</summary>
    public double[] Seconds() => [.. Writes.Select(w => w.Seconds)];

    /// <summary>
    /// Each event's delay at one end of its band: the stage's writes at their earliest and the gate's at their latest
    /// (<paramref name="gateLate"/>), or the other way round; the two make the laser fire furthest along and furthest back
    /// on the stage's motion that the recording allows.
    /// </summary>
    public double[] Corner(IReadOnlyList<WireEvent> events, bool gateLate)
    {
        ArgumentNullException.ThrowIfNull(events);
        return [.. Writes.Select((w, i) => events[i].Stage == gateLate ? w.EarliestSeconds : w.LatestSeconds)];
    }

    /// <summary>The widest band of any write, seconds.</summary>
    public double WidestSeconds => Writes.Count == 0 ? 0 : Writes.Max(w => w.LatestSeconds - w.EarliestSeconds);
}
