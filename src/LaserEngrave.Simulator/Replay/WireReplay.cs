using LaserEngrave.Core.Geometry;
using LaserEngrave.Wire.Scheduling;
using LaserEngrave.Wire.Serial;
using LaserEngrave.Wire.Zaber;

namespace LaserEngrave.Simulator.Replay;

/// <summary>Replays a flight recorder's host writes into the twin's devices at their recorded times, so they move and fire as that run's did.</summary>
/// <remarks>
/// The host is not run again: what it wrote, and when, is the recording. Each write goes into the in-process machine's
/// links at its recorded time on the virtual clock (from the recording's start), crosses the twin's adapter and wire, and
/// the devices do with it what they did then; their replies are read and dropped. The devices' physics (motion, gate,
/// burn map) is the twin's, so the burn is what the twin's hardware makes of the run's real timing.
/// </remarks>
public static class WireReplay
{
    /// <summary>Time after the last recorded event for the last moves to finish and the gate to go quiet.</summary>
    public static readonly TimeSpan Settle = TimeSpan.FromSeconds(2);

    /// <summary>Feeds the writes of <paramref name="events"/> into <paramref name="machine"/> (in-process, virtual time) and waits until the last has settled.</summary>
    /// <param name="machine">The twin, in-process on virtual time.</param>
    /// <param name="events">The recording.</param>
    /// <param name="cancellationToken">Stops the replay.</param>
    /// <param name="layerStarts">Called with each layer's index at its recorded start, on the simulation's loop (a layer's burn is checked alone).</param>
    /// <param name="delays">How much later than recorded each event's write goes in, seconds (<see cref="RecordedLatency"/>; null: none, the twin's adapters add theirs). Writes keep their order.</param>
    /// <param name="started">Called with the twin's clock (<see cref="SimulatedMachine.NowSeconds"/>) at the recording's time zero.</param>
    public static Task RunAsync(SimulatedMachine machine, IReadOnlyList<WireEvent> events, CancellationToken cancellationToken, Action<int>? layerStarts = null, IReadOnlyList<double>? delays = null, Action<double>? started = null)
    {
        ArgumentNullException.ThrowIfNull(machine);
        ArgumentNullException.ThrowIfNull(events);
        if (!machine.IsVirtualTime)
        {
            throw new InvalidOperationException("a replay runs on the simulator's virtual clock");
        }

        return machine.RunAsync(async () =>
        {
            var time = machine.TimeProvider;
            var stage = machine.StageLink;
            var laser = machine.LaserLink;
            var runner = TaskRunner.For(time);
            _ = runner.Start(() => DrainAsync(stage));
            _ = runner.Start(() => DrainAsync(laser));
            var start = time.GetTimestamp();
            started?.Invoke(machine.NowSeconds);
            var end = 0.0;
            for (var i = 0; i < events.Count; i++)
            {
                var e = events[i];
                end = Math.Max(end, e.Seconds);
                if (e.Layer is { } layer)
                {
                    await WaitUntilAsync(time, start, e.Seconds, cancellationToken);
                    layerStarts?.Invoke(layer);
                    continue;
                }

                if (!e.Write)
                {
                    continue;
                }

                await WaitUntilAsync(time, start, e.Seconds + (delays?[i] ?? 0), cancellationToken);
                await (e.Stage ? stage : laser).WriteAsync(e.Data, cancellationToken);
            }

            await WaitUntilAsync(time, start, end + Settle.TotalSeconds, cancellationToken);
        });
    }

    /// <summary>
    /// Where each axis of <paramref name="profile"/> (X, Y, Z) stood when the recording began, as its device reported it
    /// (its first reply to Return Current Position before any move was sent to it); null when an axis never said.
    /// </summary>
    /// <remarks>The twin's devices start there, so a run that homes takes as long as it took, and one that did not moves from the same place.</remarks>
    public static IReadOnlyList<long>? StartMicrosteps(MachineProfile profile, IReadOnlyList<WireEvent> events)
    {
        ArgumentNullException.ThrowIfNull(profile);
        ArgumentNullException.ThrowIfNull(events);
        var axes = new List<byte> { profile.X.DeviceNumber, profile.Y.DeviceNumber };
        if (profile.Z is { } z)
        {
            axes.Add(z.DeviceNumber);
        }

        var start = new long?[axes.Count];
        var moved = new HashSet<byte>();
        var pending = new List<byte>();
        foreach (var e in events.Where(e => e.Stage))
        {
            if (e.Write)
            {
                for (var i = 0; i + ZaberFrame.Length <= e.Data.Length; i += ZaberFrame.Length)
                {
                    if ((ZaberCommand)e.Data[i + 1] is ZaberCommand.Home or ZaberCommand.MoveAbsolute or ZaberCommand.MoveRelative or ZaberCommand.MoveAtConstantSpeed)
                    {
                        // Device 0 is every device.
                        if (e.Data[i] == 0)
                        {
                            moved.UnionWith(axes);
                        }
                        else
                        {
                            moved.Add(e.Data[i]);
                        }
                    }
                }

                continue;
            }

            pending.AddRange(e.Data);
            while (pending.Count >= ZaberFrame.Length)
            {
                var device = pending[0];
                var command = (ZaberCommand)pending[1];
                var data = BitConverter.ToInt32([pending[2], pending[3], pending[4], pending[5]]);
                pending.RemoveRange(0, ZaberFrame.Length);
                if (command == ZaberCommand.ReturnCurrentPosition && !moved.Contains(device) && axes.IndexOf(device) is >= 0 and var axis && start[axis] is null)
                {
                    start[axis] = data;
                }
            }
        }

        return start.All(s => s is not null) ? [.. start.Select(s => s!.Value)] : null;
    }

    private static async Task WaitUntilAsync(TimeProvider time, long start, double seconds, CancellationToken cancellationToken)
    {
        // On the clock's own ticks, so a recording made on the virtual clock is replayed to the tick.
        var due = start + (long)Math.Round(seconds * time.TimestampFrequency) - time.GetTimestamp();
        if (due > 0)
        {
            await PreciseDelay.DelayAsync(time, TimeSpan.FromTicks((long)Math.Round(due * (double)TimeSpan.TicksPerSecond / time.TimestampFrequency)), cancellationToken);
        }
    }

    // The devices' replies are not the replay's business (the recording has the real ones), but must be taken off the link.
    private static async Task DrainAsync(ISerialLink link)
    {
        var buffer = new byte[512];
        try
        {
            while (await link.ReadAsync(buffer, CancellationToken.None) > 0)
            {
            }
        }
        catch (Exception ex) when (ex is ObjectDisposedException or IOException or OperationCanceledException)
        {
            // The machine closed the link: the replay is over.
        }
    }
}
