using LaserEngrave.Core.Geometry;
using LaserEngrave.Simulator.Burn;
using LaserEngrave.Simulator.Faults;
using LaserEngrave.Simulator.Motion;
using LaserEngrave.Simulator.Serial;
using LaserEngrave.Simulator.Timing;
using LaserEngrave.Wire.Serial;
using LaserEngrave.Wire.Zaber;

namespace LaserEngrave.Simulator.Zaber;

/// <summary>A daisy chain of simulated Zaber devices on one serial line: X nearest the PC, then Y, then Z when the profile has a focus axis.</summary>
/// <remarks>
/// Frames are 6 bytes; a partial frame is dropped when the next byte comes more than
/// <see cref="SimulatorOptions.PartialFrameTimeout"/> after the previous one. A frame for device 0 reaches every
/// device, and each answers with its own number, in chain order. Frames for a number no device has are ignored.
/// </remarks>
public sealed class VirtualZaberChain
{
    private readonly SimulatorOptions _options;
    private readonly FaultInjector _faults;
    private readonly byte[] _partial = new byte[ZaberFrame.Length];
    private int _partialCount;
    private LinkSession? _session;

    internal VirtualZaberChain(MachineProfile profile, SimulatorOptions options, SimulationClock clock, FaultInjector faults, BurnRecorder recorder)
    {
        _options = options;
        _faults = faults;
        Clock = clock;
        Recorder = recorder;
        BaudRate = profile.StageBaudRate;
        List<VirtualZaberDevice> devices =
        [
            new VirtualZaberDevice(this, AxisName.X, 0, profile.X.DeviceNumber, profile.X.TravelMicrosteps, recorder.X, options),
            new VirtualZaberDevice(this, AxisName.Y, 1, profile.Y.DeviceNumber, profile.Y.TravelMicrosteps, recorder.Y, options),
        ];
        if (profile.Z is { } z && recorder.Z is { } zTrajectory)
        {
            devices.Add(new VirtualZaberDevice(this, AxisName.Z, 2, z.DeviceNumber, z.TravelMicrosteps, zTrajectory, options));
        }

        Devices = devices;
    }

    /// <summary>The devices in chain order.</summary>
    public IReadOnlyList<VirtualZaberDevice> Devices { get; }

    public VirtualZaberDevice X => Devices[0];

    public VirtualZaberDevice Y => Devices[1];

    /// <summary>The focus axis; null when the machine profile has no Z axis.</summary>
    public VirtualZaberDevice? Z => Devices.Count > 2 ? Devices[2] : null;

    public int BaudRate { get; }

    internal SimulationClock Clock { get; }

    internal BurnRecorder Recorder { get; }

    /// <summary>Guards the state of every device of the chain.</summary>
    internal Lock Lock { get; } = new();

    /// <summary>Serves <paramref name="link"/> until it closes, the token is cancelled, or a Disconnect fault strikes.</summary>
    internal async Task RunAsync(ISerialLink link, Action<string> log, LinkLatency latency, CancellationToken cancellationToken)
    {
        var session = new LinkSession(link, Clock, BaudRate, _options.BitsPerByte, latency, log);
        lock (Lock)
        {
            _session = session;
            _partialCount = 0;
        }

        try
        {
            await session.RunAsync(OnByte, cancellationToken);
        }
        finally
        {
            lock (Lock)
            {
                if (_session == session)
                {
                    _session = null;
                }
            }
        }
    }

    /// <summary>Sends a frame from <paramref name="device"/>, through the faults when it answers a command. Caller holds <see cref="Lock"/>.</summary>
    internal void Send(VirtualZaberDevice device, ZaberFrame frame, bool solicited)
    {
        var fault = solicited
            ? _faults.OnReply(FaultTarget.Stage, device.Number, (byte)frame.Command)
            : new ReplyFault(_faults.IsSilent(FaultTarget.Stage, device.Number), null, TimeSpan.Zero);
        if (fault.Drop)
        {
            return;
        }

        var bytes = frame.ToBytes();
        if (fault.CorruptByte is int index && index < bytes.Length)
        {
            bytes[index] ^= 0xFF;
        }

        _session?.Send(bytes, fault.Delay);
    }

    private Action? OnByte(byte value, double arrivedAt, double gapSeconds)
    {
        lock (Lock)
        {
            if (_partialCount > 0 && gapSeconds > _options.PartialFrameTimeout.TotalSeconds)
            {
                _partialCount = 0;
            }
            _partial[_partialCount++] = value;
            if (_partialCount < ZaberFrame.Length)
            {
                return null;
            }

            _partialCount = 0;
            var frame = ZaberFrame.Decode(_partial);
            return () => Execute(frame);
        }
    }

    private void Execute(ZaberFrame frame)
    {
        var disconnect = false;
        lock (Lock)
        {
            var now = Clock.NowSeconds;
            foreach (var device in Devices.Where(d => frame.Device == 0 || frame.Device == d.Number).ToList())
            {
                var fault = _faults.OnCommand(FaultTarget.Stage, device.Number, (byte)frame.Command);
                disconnect |= fault.Disconnect;
                if (fault.Ignore || fault.Disconnect)
                {
                    continue;
                }

                if (fault.RefuseCode is { } code)
                {
                    device.Refuse((int)frame.Command, code, now);
                }
                else
                {
                    device.Handle(frame, now);
                }
            }
        }

        if (disconnect)
        {
            _session?.Close("disconnected by an injected fault");
        }
    }
}
