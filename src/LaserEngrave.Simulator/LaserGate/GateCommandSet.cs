using LaserEngrave.Core.Geometry;

namespace LaserEngrave.Simulator.LaserGate;

/// <summary>The gate's commands as the machine profile spells them, so a profile for a different PIC still talks to the simulator.</summary>
/// <remarks>
/// A spelling such as "BURST {0} {1} AFTER {2}" reads a line the way the anchored, case-blind pattern
/// <c>^BURST\s+(\S+)\s+(\S+)\s+AFTER\s+(\S+)$</c> would: a run of spaces in the spelling stands for any run of
/// whitespace, each placeholder for one word, every other character for itself in either case. It is matched by hand
/// over the line's characters, not by a regex: the gate's every line is read twice (its firmware time, then its effect),
/// and an interpreted regex per command was a measurable part of the twin's time (issue 38).
/// </remarks>
internal sealed class GateCommandSet
{
    private readonly (GateCommand Command, Token[] Tokens, string Keyword)[] _commands;

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
        Span<Range> found = stackalloc Range[MaxArguments];
        foreach (var (command, tokens, _) in _commands)
        {
            if (Matches(tokens, 0, line, 0, found))
            {
                var count = ArgumentCount(tokens);
                arguments = count == 0 ? [] : new string[count];
                for (var i = 0; i < count; i++)
                {
                    arguments[i] = line[found[i]];
                }

                return command;
            }
        }

        arguments = [];
        var space = line.IndexOf(' ', StringComparison.Ordinal);
        var keyword = space < 0 ? line : line[..space];
        return _commands.Any(c => c.Keyword.Equals(keyword, StringComparison.OrdinalIgnoreCase))
            ? GateCommand.Malformed
            : GateCommand.Unknown;
    }

    // More placeholders than any spelling of the protocol has (BURST ... AFTER has three).
    private const int MaxArguments = 8;

    private enum TokenKind
    {
        Text,
        Blank,
        Argument,
    }

    /// <summary>A piece of a spelling: literal text, a run of whitespace, or the next placeholder's word.</summary>
    private readonly record struct Token(TokenKind Kind, string Text = "");

    // "FREQ {0}" becomes [Text FREQ, Blank, Argument]: literal text as is, runs of spaces one blank, each placeholder one argument.
    private static (GateCommand, Token[], string) Compile(GateCommand command, string template)
    {
        var spelling = template.Trim();
        var tokens = new List<Token>();
        var text = new System.Text.StringBuilder();
        for (var i = 0; i < spelling.Length;)
        {
            if (spelling[i] == ' ')
            {
                Flush();
                while (i < spelling.Length && spelling[i] == ' ')
                {
                    i++;
                }

                tokens.Add(new Token(TokenKind.Blank));
            }
            else if (PlaceholderLength(spelling, i) is > 0 and var length)
            {
                Flush();
                tokens.Add(new Token(TokenKind.Argument));
                i += length;
            }
            else
            {
                text.Append(spelling[i++]);
            }
        }

        Flush();
        if (tokens.Count(t => t.Kind == TokenKind.Argument) > MaxArguments)
        {
            throw new ArgumentException($"the gate command \"{spelling}\" has more than {MaxArguments} placeholders", nameof(template));
        }

        return (command, [.. tokens], spelling.Split(' ', 2)[0]);

        void Flush()
        {
            if (text.Length > 0)
            {
                tokens.Add(new Token(TokenKind.Text, text.ToString()));
                text.Clear();
            }
        }
    }

    // "{0}", "{12}": the placeholder's length at i, or 0.
    private static int PlaceholderLength(string s, int i)
    {
        if (s[i] != '{')
        {
            return 0;
        }

        var j = i + 1;
        while (j < s.Length && char.IsDigit(s[j]))
        {
            j++;
        }

        return j > i + 1 && j < s.Length && s[j] == '}' ? j - i + 1 : 0;
    }

    private static int ArgumentCount(Token[] tokens)
    {
        var count = 0;
        foreach (var token in tokens)
        {
            count += token.Kind == TokenKind.Argument ? 1 : 0;
        }

        return count;
    }

    // Tokens from t on against the line from at on; each run (blank or word) longest first, then shorter, as a regex
    // backtracks, so an argument next to literal text ("B{0},{1}" against "B1,2,3") splits where the pattern would.
    private static bool Matches(Token[] tokens, int t, ReadOnlySpan<char> line, int at, Span<Range> found, int argument = 0)
    {
        if (t == tokens.Length)
        {
            // As a regex's $: at the end, or before a final line feed.
            return at == line.Length || (at == line.Length - 1 && line[at] == '\n');
        }

        var token = tokens[t];
        if (token.Kind == TokenKind.Text)
        {
            return at + token.Text.Length <= line.Length
                && line.Slice(at, token.Text.Length).Equals(token.Text, StringComparison.OrdinalIgnoreCase)
                && Matches(tokens, t + 1, line, at + token.Text.Length, found, argument);
        }

        var blank = token.Kind == TokenKind.Blank;
        var end = at;
        while (end < line.Length && char.IsWhiteSpace(line[end]) == blank)
        {
            end++;
        }

        for (; end > at; end--)
        {
            if (!blank)
            {
                found[argument] = at..end;
            }

            if (Matches(tokens, t + 1, line, end, found, blank ? argument : argument + 1))
            {
                return true;
            }
        }

        return false;
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
