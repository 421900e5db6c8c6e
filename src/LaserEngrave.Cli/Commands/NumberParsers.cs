using System.CommandLine;
using System.CommandLine.Parsing;
using LaserEngrave.Core.Input;

namespace LaserEngrave.Cli.Commands;

/// <summary>
/// Gives every number option and argument of the command tree the one reading of <see cref="NumberText"/>: a decimal
/// point or comma, never a thousands separator, whatever the computer's language, and an error line in the user's
/// words (System.CommandLine's own names a .NET type).
/// </summary>
internal static class NumberParsers
{
    /// <summary>Sets the parser of every number option and argument under <paramref name="command"/>.</summary>
    public static void Install(Command command)
    {
        foreach (var option in command.Options)
        {
            Install(option);
        }

        foreach (var argument in command.Arguments)
        {
            Install(argument);
        }

        foreach (var subcommand in command.Subcommands)
        {
            Install(subcommand);
        }
    }

    private static void Install(Symbol symbol)
    {
        var name = symbol.Name;
        switch (symbol)
        {
            case Option<double> o:
                o.CustomParser = r => Real(r, name);
                break;
            case Option<double?> o:
                o.CustomParser = r => Real(r, name);
                break;
            case Option<double[]> o:
                o.CustomParser = r => [.. r.Tokens.Select(t => Real(r, name, t.Value))];
                break;
            case Option<int> o:
                o.CustomParser = r => (int)Whole(r, name, int.MinValue, int.MaxValue);
                break;
            case Option<int?> o:
                o.CustomParser = r => (int)Whole(r, name, int.MinValue, int.MaxValue);
                break;
            case Option<long> o:
                o.CustomParser = r => Whole(r, name, long.MinValue, long.MaxValue);
                break;
            case Option<long?> o:
                o.CustomParser = r => Whole(r, name, long.MinValue, long.MaxValue);
                break;
            case Argument<double> a:
                a.CustomParser = r => Real(r, name);
                break;
            case Argument<int> a:
                a.CustomParser = r => (int)Whole(r, name, int.MinValue, int.MaxValue);
                break;
        }
    }

    private static double Real(ArgumentResult result, string name) => Real(result, name, Single(result));

    private static double Real(ArgumentResult result, string name, string text)
    {
        if (NumberText.TryParse(text, out var value, out var problem))
        {
            return value;
        }

        result.AddError($"{name} {text}: {problem}");
        return 0;
    }

    private static long Whole(ArgumentResult result, string name, long min, long max)
    {
        var text = Single(result);
        if (NumberText.TryParseWhole(text, min, max, out var value, out var problem))
        {
            return value;
        }

        result.AddError($"{name} {text}: {problem}");
        return 0;
    }

    private static string Single(ArgumentResult result) => result.Tokens.Count > 0 ? result.Tokens[^1].Value : string.Empty;
}
