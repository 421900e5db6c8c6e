using LaserEngrave.Core.Geometry;
using LaserEngrave.Wire.Serial;
using LaserEngrave.Wire.Zaber;

namespace LaserEngrave.Simulator.Replay;

/// <summary>
/// How late each recorded write reached its device, taken from the recording itself: the round trip from the write to its
/// reply's arrival, less the wire's time both ways and the device's processing, halved (the adapter's latency one way).
/// </summary>
/// <remarks>
/// A replay delays each write by this and gives the twin's adapters no latency of their own, so the devices act when the
/// run's real adapters and computer let them, not when the twin's latency model would. A write whose reply does not
/// follow at once (a Zaber move replies on arrival, Home and Stop when they end) takes the last estimate on its link
/// before it (the first one after, at the start). Gate replies pair with the writes in order, Zaber replies by device and
/// command.
/// </remarks>
public static class RecordedLatency
{
    private const double BitsPerByte = 10;

    /// <summary>The one-way delay, seconds, of each event of <paramref name="events"/> that is a write (0 for the rest; 0 for every write on a link without one usable reply).</summary>
    /// <param name="profile">The machine (baud rates, the gate's line terminator).</param>
    /// <param name="events">The recording.</param>
    /// <param name="gateProcessingSeconds">The gate's own time from a command's last byte to its reply, seconds, for the command's bytes (the twin's, which the replay keeps).</param>
    public static double[] OneWaySeconds(MachineProfile profile, IReadOnlyList<WireEvent> events, Func<byte[], double> gateProcessingSeconds)
    {
        ArgumentNullException.ThrowIfNull(profile);
        ArgumentNullException.ThrowIfNull(events);
        var roundTrips = new double?[events.Count];
        var rest = new double[events.Count];
        StageRoundTrips(profile, events, roundTrips, rest);
        GateRoundTrips(profile, events, roundTrips, rest, gateProcessingSeconds);
        var result = new double[events.Count];
        foreach (var (stage, baud) in new[] { (true, profile.StageBaudRate), (false, profile.Gate.BaudRate) })
        {
            var secondsPerByte = BitsPerByte / baud;
            var writes = Enumerable.Range(0, events.Count).Where(i => events[i].Write && events[i].Stage == stage).ToList();
            double? last = null;
            var wireFreeAt = double.NegativeInfinity;
            foreach (var i in writes.Where(i => roundTrips[i] is not null).Take(1))
            {
                // Before the first estimate: the first one's, ignoring any queue.
                last = Math.Max(0, (roundTrips[i]!.Value - rest[i]) / 2);
            }

            foreach (var i in writes)
            {
                var e = events[i];
                if (roundTrips[i] is { } roundTrip)
                {
                    // Half the round trip each way, unless the write then still waited for the wire (the bytes before it
                    // on their way out): then the wait explains part of the round trip, and the adapter the rest.
                    var queue = wireFreeAt - e.Seconds;
                    var half = Math.Max(0, (roundTrip - rest[i]) / 2);
                    last = half >= queue ? half : Math.Max(0, roundTrip - rest[i] - queue);
                }

                result[i] = last ?? 0;
                wireFreeAt = Math.Max(e.Seconds + result[i], wireFreeAt) + (e.Data.Length * secondsPerByte);
            }
        }

        return result;
    }

    // Each Zaber write's round trip to its reply (a command that replies at once), and the wire's part of it.
    private static void StageRoundTrips(MachineProfile profile, IReadOnlyList<WireEvent> events, double?[] roundTrips, double[] rest)
    {
        var wire = 2 * ZaberFrame.Length * BitsPerByte / profile.StageBaudRate;
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
            }
        }
    }

    // Each gate command's round trip to its reply line (in order), and the wire's and the gate's processing part of it.
    private static void GateRoundTrips(MachineProfile profile, IReadOnlyList<WireEvent> events, double?[] roundTrips, double[] rest, Func<byte[], double> processingSeconds)
    {
        var terminator = (byte)profile.Gate.LineTerminator[^1];
        var secondsPerByte = BitsPerByte / profile.Gate.BaudRate;
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
