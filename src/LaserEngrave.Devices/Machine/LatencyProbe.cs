using LaserEngrave.Core.Geometry;
using LaserEngrave.Devices.Abstractions;
using LaserEngrave.Devices.LaserGate;
using LaserEngrave.Devices.Zaber;
using LaserEngrave.Wire.Scheduling;
using LaserEngrave.Wire.Serial;
using LaserEngrave.Wire.Zaber;

namespace LaserEngrave.Devices.Machine;

/// <summary>Times round trips to the machine's devices: Zaber Echo Data (command 55; Return Firmware Version before firmware 5.04, which has no Echo) to each axis and the gate's keepalive.</summary>
/// <remarks>
/// Every exchange waits for its reply before the next goes out, so no two share the wire, and is timed on the session's
/// clock from just before the write to the reply's arrival (virtual time on the in-process simulator, so the figures are
/// the same for the same seed). The first exchange with each device is not timed and is tried twice, as preflight does:
/// the first line after a port opens can be lost.
/// </remarks>
public sealed class LatencyProbe : ILatencyProbe
{

    // Timed waits per round trip asked for (1000 for the default 200), each as long as a short switching wait: enough
    // that the 99th percentile is not the tail's single worst.
    private const int WaitsPer = 5;
    private const double WaitMs = 1;

    private readonly ZaberChain _stage;
    private readonly PicLaserGate _gate;
    private readonly TimeProvider _time;

    public LatencyProbe(ZaberChain stage, PicLaserGate gate, TimeProvider timeProvider)
    {
        ArgumentNullException.ThrowIfNull(stage);
        ArgumentNullException.ThrowIfNull(gate);
        ArgumentNullException.ThrowIfNull(timeProvider);
        _stage = stage;
        _gate = gate;
        _time = timeProvider;
    }

    /// <summary>Measures <paramref name="exchanges"/> round trips to each axis and to the gate, one device after the other.</summary>
    /// <param name="exchanges">Round trips per device, at least 1.</param>
    /// <param name="cancellationToken">Stops the measurement.</param>
    public async Task<LatencyMeasurement> MeasureAsync(int exchanges, CancellationToken cancellationToken)
    {
        ArgumentOutOfRangeException.ThrowIfLessThan(exchanges, 1);
        var stageWireMs = WireMs(2 * ZaberFrame.Length, _stage.Profile.StageBaudRate);
        var x = RoundTrips.Of(_stage.X.Description, await TimeAsync(exchanges, i => _stage.X.PingAsync(i, cancellationToken), cancellationToken), stageWireMs);
        var y = RoundTrips.Of(_stage.Y.Description, await TimeAsync(exchanges, i => _stage.Y.PingAsync(i, cancellationToken), cancellationToken), stageWireMs);

        var gate = _gate.Profile;
        if (gate.NeverReplies)
        {
            throw new DeviceException($"laser gate on {_gate.PortName} never replies (the profile's gate.neverReplies), so no round trip times it: keep the profile's gate latencies, measured on the bench");
        }

        // A frequency-only gate has no keepalive: its off command, with the laser off already, is the exchange that changes nothing.
        var (command, expected) = gate.CountsBursts ? (gate.KeepAliveCommand, gate.KeepAliveReply) : (gate.OffCommand, gate.OffReply);
        var reply = string.Empty;
        var times = await TimeAsync(exchanges, async _ => reply = await _gate.SendAsync(command, expected, cancellationToken), cancellationToken);

        // The reply as it came: the prefix, the text after it if any, the terminator.
        var replyBytes = gate.AckPrefix.Length + (reply.Length == 0 ? 0 : 1 + reply.Length) + gate.LineTerminator.Length;
        var gateWireMs = WireMs(command.Length + gate.LineTerminator.Length + replyBytes, gate.BaudRate);
        var host = await TimeWaitsAsync(WaitsPer * exchanges, cancellationToken);
        return new LatencyMeasurement(x, y, RoundTrips.Of($"laser gate on {_gate.PortName}", times, gateWireMs), host);
    }

    /// <summary>
    /// How late this computer wakes from <paramref name="count"/> timed waits of <see cref="WaitMs"/>, as a timed switching
    /// waits (<see cref="PreciseDelay"/>, on the session's clock: the twin's modelled lateness on its virtual one).
    /// </summary>
    private async Task<HostWaits> TimeWaitsAsync(int count, CancellationToken cancellationToken)
    {
        var wait = TimeSpan.FromMilliseconds(WaitMs);
        var lateness = new double[count];
        for (var i = 0; i < count; i++)
        {
            var start = _time.GetTimestamp();
            await PreciseDelay.DelayAsync(_time, wait, cancellationToken);
            lateness[i] = _time.GetElapsedTime(start).TotalMilliseconds - WaitMs;
        }

        return HostWaits.Of(lateness);
    }

    /// <summary>Time <paramref name="bytes"/> take on the wire at <paramref name="baudRate"/>, 10 bits a byte (8N1), ms.</summary>
    public static double WireMs(int bytes, int baudRate) => Units.SecondsToMs(bytes * SerialLine.BitsPerByte) / baudRate;

    private async Task<double[]> TimeAsync(int exchanges, Func<int, Task> exchange, CancellationToken cancellationToken)
    {
        try
        {
            await exchange(0);
        }
        catch (DeviceTimeoutException)
        {
            await exchange(0);
        }

        var times = new double[exchanges];
        for (var i = 0; i < exchanges; i++)
        {
            cancellationToken.ThrowIfCancellationRequested();
            var start = _time.GetTimestamp();
            await exchange(i + 1);
            times[i] = _time.GetElapsedTime(start).TotalMilliseconds;
        }

        return times;
    }
}
