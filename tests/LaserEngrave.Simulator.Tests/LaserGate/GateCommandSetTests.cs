using System.Text.RegularExpressions;
using LaserEngrave.Core.Geometry;
using LaserEngrave.Simulator.LaserGate;

namespace LaserEngrave.Simulator.Tests.LaserGate;

/// <summary>The gate's lines read by hand as the profile's spellings say, the same as the regexes that read them before.</summary>
public class GateCommandSetTests
{
    private static readonly string[] Lines =
    [
        "*IDN?", "*idn?", "FREQ 1000", "freq 1000", "FREQ  1000", "FREQ\t1000", "FREQ", "FREQ ", "FREQ 1000 2000",
        "FREQ 1000\n", "FREQ 1000\n\n", "OFF", "OFF ", "Off", "OFFX", "STATE?", "STATE? now", "PING", "WDOG 250", "WDOG",
        "BURST 10 1000", "BURST 10 1000 AFTER 300", "burst 10 1000 after 300", "BURST 10 1000 AFTER", "BURST 10",
        "BURST  10   1000  AFTER  300", "BURST 10 1000 BEFORE 300", "CAPS?", "", " ", "HELLO", "FREQ -5", "FREQ 1e3",
        "BURST 1\u00a02", "BURST x y AFTER z", "FREQ\u212a",
    ];

    public static TheoryData<string> Spellings() =>
    [
        "B{0},{1}", "SET{0}={1}", "GO {0}{1}", "A  {0}   B {1}", "X{0}Y", "K", "{0}", "P {0} {1} {2}",
    ];

    [Fact]
    public void Match_DefaultSpellings_AgreesWithTheAnchoredPatternOnEveryLine()
    {
        var profile = MachineProfile.Default.Gate;
        var commands = new GateCommandSet(profile);
        var reference = Reference(profile);

        foreach (var line in Lines)
        {
            var expected = reference(line, out var expectedArguments);
            var command = commands.Match(line, out var arguments);

            Assert.True(expected == command, $"\"{line}\": {command}, the pattern says {expected}");
            Assert.Equal(expectedArguments, arguments);
        }
    }

    [Theory]
    [MemberData(nameof(Spellings))]
    public void Match_ArgumentNextToText_SplitsWhereThePatternWould(string spelling)
    {
        var profile = MachineProfile.Default.Gate with { FrequencyCommand = spelling };
        var commands = new GateCommandSet(profile);
        var reference = Reference(profile);
        string[] lines = ["B1,2", "B1,2,3", "b,1,2", "SETa=b=c", "SET=1", "GO 12", "GO 1", "A 1 B 2", "A1B2", "A  x   B  y",
            "XabcY", "XY", "XYY", "k", "K ", "word", "two words", "P 1 2 3", "P 1 2", "P 1 2 3 4"];

        foreach (var line in lines)
        {
            var expected = reference(line, out var expectedArguments);
            var command = commands.Match(line, out var arguments);

            Assert.True(expected == command, $"{spelling} on \"{line}\": {command}, the pattern says {expected}");
            Assert.Equal(expectedArguments, arguments);
        }
    }

    [Fact]
    public void Match_BurstAfter_ReturnsItsThreeArguments()
    {
        var commands = new GateCommandSet(MachineProfile.Default.Gate);

        var command = commands.Match("burst 12  1000 after 350", out var arguments);

        Assert.Equal(GateCommand.BurstAfter, command);
        Assert.Equal(["12", "1000", "350"], arguments);
    }

    [Fact]
    public void Match_KeywordWithWrongArguments_IsMalformedAndOtherWordsUnknown()
    {
        var commands = new GateCommandSet(MachineProfile.Default.Gate);

        Assert.Equal(GateCommand.Malformed, commands.Match("FREQ 1 2", out _));
        Assert.Equal(GateCommand.Unknown, commands.Match("FIRE 1", out var arguments));
        Assert.Empty(arguments);
    }

    // What the gate read lines with before the hand parser: each spelling compiled to an anchored, case-blind regex.
    private delegate GateCommand Reader(string line, out string[] arguments);

    private static Reader Reference(LaserGateProfile profile)
    {
        (GateCommand, string)[] spellings =
        [
            (GateCommand.Identify, profile.IdentifyCommand), (GateCommand.Frequency, profile.FrequencyCommand),
            (GateCommand.Off, profile.OffCommand), (GateCommand.State, profile.StatusCommand),
            (GateCommand.KeepAlive, profile.KeepAliveCommand), (GateCommand.Watchdog, profile.WatchdogCommand),
            (GateCommand.Burst, profile.BurstCommand), (GateCommand.BurstAfter, profile.BurstAfterCommand),
            (GateCommand.Capabilities, profile.CapabilitiesCommand),
        ];
        var compiled = spellings.Select(s =>
        {
            var pattern = "^" + string.Concat(Regex.Split(s.Item2.Trim(), @"(\{\d+\})").Select(part =>
                Regex.IsMatch(part, @"^\{\d+\}$") ? @"(\S+)" : Regex.Replace(Regex.Escape(part), @"(\\ )+", @"\s+"))) + "$";
            return (s.Item1, new Regex(pattern, RegexOptions.IgnoreCase | RegexOptions.CultureInvariant), s.Item2.Trim().Split(' ', 2)[0]);
        }).ToArray();
        return (string line, out string[] arguments) =>
        {
            foreach (var (command, regex, _) in compiled)
            {
                var match = regex.Match(line);
                if (match.Success)
                {
                    arguments = [.. match.Groups.Cast<Group>().Skip(1).Select(g => g.Value)];
                    return command;
                }
            }

            arguments = [];
            var keyword = line.Split(' ', 2)[0];
            return compiled.Any(c => c.Item3.Equals(keyword, StringComparison.OrdinalIgnoreCase)) ? GateCommand.Malformed : GateCommand.Unknown;
        };
    }
}
