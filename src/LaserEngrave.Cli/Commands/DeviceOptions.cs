using System.CommandLine;
using LaserEngrave.Core.Geometry;

namespace LaserEngrave.Cli.Commands;

/// <summary>The options of the wiring-check commands (`stage`, `laser`): which port, which machine profile.</summary>
internal sealed class DeviceOptions
{
    public Option<string> Port { get; } = new("--port")
    {
        Description = "Serial port: COM3, /dev/ttyUSB0, or any path to a tty such as a socat pty (see `laserengrave ports`)",
        Required = true,
        Recursive = true,
    };

    public Option<string?> Profile { get; } = new("--profile")
    {
        Description = "Machine profile (JSON); default: two Zaber T-LA60A, device 1 = X, device 2 = Y",
        Recursive = true,
    };

    public void AddTo(Command command)
    {
        command.Options.Add(Port);
        command.Options.Add(Profile);
    }

    public string PortName(ParseResult result) => result.GetRequiredValue(Port);

    public MachineProfile LoadProfile(ParseResult result) =>
        result.GetValue(Profile) is { } path ? MachineProfile.Load(path) : MachineProfile.Default;
}
