using System.Text.RegularExpressions;
using LaserEngrave.Core.Geometry;

namespace LaserEngrave.Simulator.LaserGate;

/// <summary>The gate's commands as the machine profile spells them, so a profile for a different PIC still talks to the simulator.</summary>
internal sealed class GateCommandSet
{
    private readonly (GateCommand Command, Regex Pattern, string Keyword)[] _commands;

    public GateCommandSet(LaserGateProfile profile)
    {
        _commands =
        [
            Compile(GateCommand.Identify, profile.IdentifyCommand),
            Compile(GateCommand.Frequency, profile.FrequencyCommand),
            Compile(GateCommand.Off, profile.OffCommand),
            Compile(GateCommand.State, profile.StatusCommand),
            Compile(GateCommand.KeepAlive, profile.KeepAliveCommand),
            Compile(GateCommand.Watchdog, profile.WatchdogCommand),
            Compile(GateCommand.Burst, profile.BurstCommand),
            Compile(GateCommand.BurstAfter, profile.BurstAfterCommand),
            Compile(GateCommand.Capabilities, profile.CapabilitiesCommand),
        ];
    }

    /// <summary>Which command <paramref name="line"/> is and its arguments; <see cref="GateCommand.Malformed"/> when only the keyword matches.</summary>
    public GateCommand Match(string line, out string[] arguments)
    {
        foreach (var (command, pattern, _) in _commands)
        {
            var match = pattern.Match(line);
            if (match.Success)
            {
                arguments = [.. match.Groups.Cast<Group>().Skip(1).Select(g => g.Value)];
                return command;
            }
        }

        arguments = [];
        var keyword = line.Split(' ', 2)[0];
        return _commands.Any(c => c.Keyword.Equals(keyword, StringComparison.OrdinalIgnoreCase))
            ? GateCommand.Malformed
            : GateCommand.Unknown;
    }

    // "FREQ {0}" becomes ^FREQ\s+(\S+)$: literal text as is, each placeholder one argument.
    private static (GateCommand, Regex, string) Compile(GateCommand command, string template)
    {
        var pattern = "^" + string.Concat(Regex.Split(template.Trim(), @"(\{\d+\})").Select(part =>
            Regex.IsMatch(part, @"^\{\d+\}$") ? @"(\S+)" : Regex.Replace(Regex.Escape(part), @"(\\ )+", @"\s+"))) + "$";
        var keyword = template.Trim().Split(' ', 2)[0];
        return (command, new Regex(pattern, RegexOptions.IgnoreCase | RegexOptions.CultureInvariant), keyword);
    }
}

/// <summary>The commands of the gate protocol (docs/laser-gate-protocol.md).</summary>
internal enum GateCommand
{
    Unknown,
    Malformed,
    Identify,
    Frequency,
    Off,
    State,
    KeepAlive,
    Watchdog,
    Burst,
    BurstAfter,
    Capabilities,
}
