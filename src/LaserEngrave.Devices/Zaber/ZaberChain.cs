using LaserEngrave.Core.Geometry;
using LaserEngrave.Devices.Abstractions;
using LaserEngrave.Devices.Serial;
using LaserEngrave.Wire.Zaber;

namespace LaserEngrave.Devices.Zaber;

/// <summary>The X-Y stage: two Zaber devices daisy-chained on one serial port, numbered as the machine profile says, and a third for focus when the profile has a Z axis.</summary>
public sealed class ZaberChain : IStage, IAsyncDisposable
{
    public ZaberChain(ZaberConnection connection, MachineProfile profile)
    {
        ArgumentNullException.ThrowIfNull(connection);
        ArgumentNullException.ThrowIfNull(profile);
        Connection = connection;
        Profile = profile;
        X = new ZaberBinaryDevice(connection, profile.X.DeviceNumber, "X");
        Y = new ZaberBinaryDevice(connection, profile.Y.DeviceNumber, "Y");
        Z = profile.Z is { } z ? new ZaberBinaryDevice(connection, z.DeviceNumber, "Z") : null;
    }

    public ZaberConnection Connection { get; }

    /// <inheritdoc/>
    public bool IsReceiving => Connection.IsReceiving;

    /// <inheritdoc/>
    public Task<long?> LineWritten => Connection.LineWritten;

    public MachineProfile Profile { get; }

    public ZaberBinaryDevice X { get; }

    public ZaberBinaryDevice Y { get; }

    /// <summary>The focus axis; null when the profile has no Z axis.</summary>
    public ZaberBinaryDevice? Z { get; }

    IStageAxis IStage.X => X;

    IStageAxis IStage.Y => Y;

    IStageAxis? IStage.Z => Z;

    /// <summary>Opens the port at the profile's stage baud rate (8N1, no handshake) and starts the connection.</summary>
    public static ZaberChain Open(string portName, MachineProfile profile, TimeProvider? timeProvider = null, ZaberConnectionOptions? options = null)
    {
        ArgumentNullException.ThrowIfNull(profile);
        var port = SerialPortLink.Open(new SerialPortSettings(portName) { BaudRate = profile.StageBaudRate });
        return new ZaberChain(new ZaberConnection(port, timeProvider, options), profile);
    }

    /// <summary>Finds the devices on the port (Return Device ID to device 0, every reply collected), reads firmware,
    /// speed, acceleration, maximum position, position and Device Mode of each, and notices auto-reply disabled.</summary>
    /// <param name="fixAutoReply">Clear Device Mode bit 0 where it is set (read-modify-write), so moves reply again.</param>
    /// <param name="cancellationToken">Cancels discovery.</param>
    public async Task<ZaberDiscovery> DiscoverAsync(bool fixAutoReply, CancellationToken cancellationToken)
    {
        var replies = await Connection.BroadcastAsync(ZaberCommand.ReturnDeviceId, 0, Connection.Options.CommandTimeout, cancellationToken);
        var notes = new List<string>();
        var ids = new SortedDictionary<byte, int>();
        foreach (var reply in replies)
        {
            if (reply.Command == ZaberCommand.Error)
            {
                notes.Add($"{Connection.PortName}: {Connection.DescribeDevice(reply.Device)} refused Return Device ID: error {reply.Data}, {ZaberErrorCodes.Describe(reply.Data)}");
            }
            else if (!ids.TryAdd(reply.Device, reply.Data))
            {
                notes.Add($"{Connection.PortName}: more than one device answers as number {reply.Device}; renumber the chain");
            }
        }

        var devices = new List<ZaberDeviceInfo>();
        foreach (var (number, deviceId) in ids)
        {
            var axis = number == X.DeviceNumber ? X : number == Y.DeviceNumber ? Y : number == Z?.DeviceNumber ? Z : new ZaberBinaryDevice(Connection, number);
            devices.Add(await InspectAsync(axis, deviceId, fixAutoReply, notes, cancellationToken));
        }

        foreach (var axis in Z is null ? new[] { X, Y } : [X, Y, Z])
        {
            if (!ids.ContainsKey(axis.DeviceNumber))
            {
                var found = ids.Count == 0 ? "no device answered" : $"found device(s) {string.Join(", ", ids.Keys)}";
                notes.Add($"{Connection.PortName}: {axis.Description} did not answer ({found}); check the cable, the power and the device numbers");
            }
        }

        return new ZaberDiscovery(Connection.PortName, devices, notes);
    }

    public ValueTask DisposeAsync() => Connection.DisposeAsync();

    private static async Task<ZaberDeviceInfo> InspectAsync(ZaberBinaryDevice axis, int deviceId, bool fixAutoReply, List<string> notes, CancellationToken cancellationToken)
    {
        // Auto-reply disabled devices still answer Return commands, so everything here works before the fix.
        var firmware = await axis.ReturnFirmwareVersionAsync(cancellationToken);
        var mode = await axis.ReturnSettingAsync(ZaberCommand.SetDeviceMode, cancellationToken);
        var speed = await axis.ReturnSettingAsync(ZaberCommand.SetTargetSpeed, cancellationToken);
        var acceleration = await axis.ReturnSettingAsync(ZaberCommand.SetAcceleration, cancellationToken);
        var maximum = await axis.ReturnSettingAsync(ZaberCommand.SetMaximumPosition, cancellationToken);
        var position = await axis.GetPositionAsync(cancellationToken);
        var disabled = (mode & ZaberBinaryDevice.AutoReplyDisabledBit) != 0;
        var fixedNow = false;
        if (disabled && fixAutoReply)
        {
            mode = await axis.SetDeviceModeAsync(0, ZaberBinaryDevice.AutoReplyDisabledBit, cancellationToken);
            fixedNow = true;
            notes.Add($"{axis.Connection.PortName}: {axis.Description} had auto-reply disabled (Device Mode bit 0), so it would never confirm a move; re-enabled it");
        }
        else if (disabled)
        {
            notes.Add($"{axis.Connection.PortName}: {axis.Description} has auto-reply disabled (Device Mode bit 0), so it will not confirm moves; clear bit 0 before engraving");
        }

        return new ZaberDeviceInfo(axis.DeviceNumber, axis.Label, deviceId, firmware, mode, speed, acceleration, maximum, position, disabled, fixedNow);
    }
}
