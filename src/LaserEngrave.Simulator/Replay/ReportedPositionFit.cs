using LaserEngrave.Core.Geometry;
using LaserEngrave.Simulator.Motion;
using LaserEngrave.Wire.Serial;
using LaserEngrave.Wire.Zaber;

namespace LaserEngrave.Simulator.Replay;

/// <summary>
/// The stages' own word on their timing: every position a stage reported while it moved says where it was when the query
/// arrived, so a replay whose stage stands elsewhere at that moment has the write that last changed its motion (the move,
/// or the speed change of a flown gap) arriving at the wrong time. The write is moved until the replay's stage reports
/// what the run's did, and its band narrows to what the query's own delivery leaves open.
/// </summary>
/// <remarks>
/// Without this a replay of a run on jittery adapters put a flown gap's speed-down half a millisecond off, which at the
/// gap's travel speed is 15 µm along the next burn run, where the run's host had seen the stage's true place in its
/// position reply and timed the switch-on to it. Each reported position corrects only the motion write that came after
/// the axis's previous report (the earlier ones are that report's); the corrections are repeated on a fresh replay until
/// every report agrees (a correction changes what follows it), at most <see cref="MaxPasses"/> times.
/// </remarks>
internal static class ReportedPositionFit
{
    /// <summary>Replays at most this many times to make the replay's stage report what the run's did.</summary>
    public const int MaxPasses = 8;


    // A stage slower than this (microsteps/s) at a query says nothing of the time; a change smaller than this is not a motion change.
    private const double StillMicrostepsPerSecond = 1000;

    // Moves beyond this are not a delivery's error but a different story (a refused command, a fault): left alone.
    private const double MaxCorrectionSeconds = 0.05;

    /// <summary>Moves the stage's motion writes from <paramref name="start"/> until the replay's stage reports what the run's stages reported (<paramref name="positions"/>); the delays, their last replay and how well its stage agreed.</summary>
    /// <param name="start">Each event's delay to start from, seconds (the queries' among them stay).</param>
    /// <param name="replay">Replays the recording at the given delays.</param>
    /// <param name="spill">Whether a write that would have to arrive before it was written moves the motion write before it instead (the estimate; not the ends of the bands, which are the adapter's extremes and nothing further).</param>
    public static async Task<(double[] Seconds, ReplayRun Run, PositionAgreement Agreement)> FitAsync(MachineProfile profile, IReadOnlyList<WireEvent> events, IReadOnlyList<RecordedPosition> positions, IReadOnlyList<double> start, Func<IReadOnlyList<double>, Task<ReplayRun>> replay, bool spill = true)
    {
        var links = Links(profile, events, positions);
        var seconds = start.ToArray();
        var passes = 0;
        var corrected = new HashSet<int>();
        double worst;
        ReplayRun run;

        // The pass whose stage disagreed least with the reports in all (a correction that caught a ramp can make it worse).
        (double Total, double Worst, double[] Seconds, ReplayRun Run)? best = null;
        while (true)
        {
            run = await replay(seconds).ConfigureAwait(false);
            passes++;
            var arrivals = StageArrivals(profile, events, seconds);
            worst = 0;
            var total = 0.0;
            var corrections = new List<(int Write, double By, int Earlier)>();

            // What a stage was found off by at its previous report goes on with it (an offset along a motion stays one
            // through a speed change): a write is corrected for what its report adds to that, so that all of them can be
            // corrected at once, and a move from standing starts afresh.
            var carried = new Dictionary<byte, double>();
            foreach (var link in links)
            {
                if (!run.Axes.TryGetValue(link.Position.Device, out var axis))
                {
                    continue;
                }

                var at = arrivals[(link.Position.WriteIndex, link.QueryFrame)] + run.StartSeconds;
                var velocity = axis.VelocityAt(at);
                var carry = carried.GetValueOrDefault(link.Position.Device);
                carried[link.Position.Device] = 0;
                if (Math.Abs(velocity) < StillMicrostepsPerSecond)
                {
                    continue;
                }

                var off = Math.Round(axis.PositionAt(at), MidpointRounding.AwayFromZero) - link.Position.Microsteps;
                carried[link.Position.Device] = off;
                worst = Math.Max(worst, Math.Abs(off));
                total += Math.Abs(off);
                if (link.MotionWrite < 0)
                {
                    continue;
                }

                var changedAt = arrivals[(link.MotionWrite, link.MotionFrame)] + run.StartSeconds;
                var before = axis.VelocityAt(changedAt - 1e-7);
                var added = Math.Abs(before) < StillMicrostepsPerSecond ? off : off - carry;
                var sensitivity = Sensitivity(axis, changedAt, velocity);
                if (Math.Abs(added) <= 1 || Math.Abs(sensitivity) < StillMicrostepsPerSecond)
                {
                    continue;
                }

                var by = -added / sensitivity;
                if (Math.Abs(by) <= MaxCorrectionSeconds)
                {
                    corrections.Add((link.MotionWrite, by, link.EarlierMotionWrite));
                }
            }

            if (best is not { } b || total < b.Total)
            {
                best = (total, worst, [.. seconds], run);
            }

            if (corrections.Count == 0 || passes >= MaxPasses)
            {
                break;
            }

            foreach (var (write, by, earlier) in corrections)
            {
                var moved = seconds[write] + by;
                seconds[write] = Math.Max(0, moved);
                corrected.Add(write);
                if (spill && moved < 0 && earlier >= 0)
                {
                    // Sooner than it was written: the motion change before it (a flown gap's speed-up) came later than
                    // the adapter shows instead (a far end that read its bytes late), which to first order is the same.
                    seconds[earlier] += -moved;
                    corrected.Add(earlier);
                }
            }
        }

        var kept = best!.Value;
        return (kept.Seconds, kept.Run, new PositionAgreement(positions.Count, corrected.Count, passes, kept.Worst * MicrostepUm(profile)));
    }

    // How far along the stage is at a later report per second the motion change comes later, microsteps/s: the speed it
    // had over the speed it reports, and as much again in the proportion of the ramps when the change caught it
    // accelerating (it then reaches a higher speed before it slows, and takes longer to).
    private static double Sensitivity(AxisTrajectory axis, double changedAt, double reportedVelocity)
    {
        const double Step = 1e-4;
        var before = axis.VelocityAt(changedAt - 1e-7);
        var rampBefore = (before - axis.VelocityAt(changedAt - Step)) / Step;
        var rampAfter = (axis.VelocityAt(changedAt + Step) - axis.VelocityAt(changedAt + 1e-7)) / Step;
        var ramps = Math.Abs(rampAfter) < 1 ? 0 : Math.Clamp(-rampBefore / rampAfter, -1, 1);
        return (before - reportedVelocity) * (1 + ramps);
    }

    private static double MicrostepUm(MachineProfile profile) => Math.Max(profile.X.MicrostepUm, profile.Y.MicrostepUm);

    // Each reported position with the motion write (and its frame) it can correct: the last one on its device (or all
    // devices) before the query, when it came after the device's previous report and in a write of its own.
    private static List<PositionLink> Links(MachineProfile profile, IReadOnlyList<WireEvent> events, IReadOnlyList<RecordedPosition> positions)
    {
        var result = new List<PositionLink>();
        var previousReport = new Dictionary<byte, int>();
        foreach (var position in positions.OrderBy(p => p.WriteIndex))
        {
            var query = events[position.WriteIndex];
            var queryFrame = -1;
            for (var at = 0; at + ZaberFrame.Length <= query.Data.Length; at += ZaberFrame.Length)
            {
                if (query.Data[at] == position.Device && (ZaberCommand)query.Data[at + 1] == ZaberCommand.ReturnCurrentPosition)
                {
                    queryFrame = at / ZaberFrame.Length;
                }
            }

            var since = previousReport.GetValueOrDefault(position.Device, -1);
            previousReport[position.Device] = position.WriteIndex;
            if (queryFrame < 0)
            {
                continue;
            }

            // A motion frame written with the query moves with it: the report then says nothing of its time.
            var (motionWrite, motionFrame, earlierWrite) = (-1, -1, -1);
            if (LastMotionFrame(query.Data, position.Device) is var own && own >= 0 && own < queryFrame)
            {
                result.Add(new PositionLink(position, queryFrame, -1, -1));
                continue;
            }

            for (var i = position.WriteIndex - 1; i > since; i--)
            {
                var e = events[i];
                if (!e.Write || !e.Stage || e.Layer is not null)
                {
                    continue;
                }

                var frame = LastMotionFrame(e.Data, position.Device);
                if (frame < 0)
                {
                    continue;
                }

                if (motionWrite < 0)
                {
                    (motionWrite, motionFrame) = (i, frame);
                    continue;
                }

                earlierWrite = i;
                break;
            }

            result.Add(new PositionLink(position, queryFrame, motionWrite, motionFrame) { EarlierMotionWrite = earlierWrite });
        }

        return result;
    }

    private static int LastMotionFrame(byte[] data, byte device)
    {
        var found = -1;
        for (var at = 0; at + ZaberFrame.Length <= data.Length; at += ZaberFrame.Length)
        {
            if ((data[at] == device || data[at] == 0) && (ZaberCommand)data[at + 1] is ZaberCommand.MoveAbsolute or ZaberCommand.MoveRelative or ZaberCommand.MoveAtConstantSpeed or ZaberCommand.Stop or ZaberCommand.SetTargetSpeed or ZaberCommand.SetAcceleration)
            {
                found = at / ZaberFrame.Length;
            }
        }

        return found;
    }

    // When each stage frame's last byte reaches its device in a replay at these delays, seconds from the recording's start:
    // the replay writes in recorded order, each at its time plus its delay or after the write before it, and the twin's
    // wire (without adapter latency of its own) sends each write's bytes behind those still going out.
    private static Dictionary<(int Write, int Frame), double> StageArrivals(MachineProfile profile, IReadOnlyList<WireEvent> events, IReadOnlyList<double> seconds)
    {
        var perByte = SerialLine.BitsPerByte / profile.StageBaudRate;
        var result = new Dictionary<(int, int), double>();
        var written = double.NegativeInfinity;
        var wireFree = double.NegativeInfinity;
        for (var i = 0; i < events.Count; i++)
        {
            var e = events[i];
            if (!e.Write || e.Layer is not null)
            {
                continue;
            }

            written = Math.Max(written, e.Seconds + seconds[i]);
            if (!e.Stage)
            {
                continue;
            }

            var start = Math.Max(written, wireFree);
            for (var frame = 0; frame * ZaberFrame.Length < e.Data.Length; frame++)
            {
                result[(i, frame)] = start + (Math.Min(e.Data.Length, (frame + 1) * ZaberFrame.Length) * perByte);
            }

            wireFree = start + (e.Data.Length * perByte);
        }

        return result;
    }

    private sealed record PositionLink(RecordedPosition Position, int QueryFrame, int MotionWrite, int MotionFrame)
    {
        /// <summary>The motion write before <see cref="MotionWrite"/> since the previous report (-1: none).</summary>
        public int EarlierMotionWrite { get; init; } = -1;
    }
}

/// <summary>How the replay's stage agreed with the positions the run's stages reported.</summary>
/// <param name="Reported">Positions the stages reported (Return Current Position replies).</param>
/// <param name="Corrected">Motion writes moved to make the replay's stage report them.</param>
/// <param name="Passes">Replays it took.</param>
/// <param name="WorstOffUm">The farthest the replay's stage stood from a position reported while moving, after the fit, µm.</param>
public sealed record PositionAgreement(int Reported, int Corrected, int Passes, double WorstOffUm);
