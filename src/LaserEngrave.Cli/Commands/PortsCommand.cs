using System.CommandLine;
using LaserEngrave.Devices.Serial;

namespace LaserEngrave.Cli.Commands;

/// <summary>`laserengrave ports`: the serial ports this computer knows of.</summary>
internal static class PortsCommand
{
    public static Command Create()
    {
        var command = new Command("ports", "List the serial ports of this computer (ptys are not listed but can be given by path)");
        command.SetAction(result =>
        {
            var output = result.InvocationConfiguration.Output;
            var names = SerialPortNames.List();
            if (names.Count == 0)
            {
                output.WriteLine("no serial ports found (a pty, such as one made by socat, can still be given by its path)");
            }

            foreach (var name in names)
            {
                output.WriteLine(name);
            }

            return 0;
        });
        return command;
    }
}
