using System.Globalization;
using System.Text;
using System.Text.RegularExpressions;

namespace LaserEngrave.Core.Marks;

/// <summary>What a mark's placeholders stand for in one copy: its number, the run's sample, the time and the machine.</summary>
/// <param name="Number">The copy's number (the counter's next number plus the copy's index).</param>
/// <param name="Sample">The run's sample ID, or null when none was given.</param>
/// <param name="Now">The moment the marks are made, in the lab's local time.</param>
/// <param name="Profile">The machine profile's name.</param>
public sealed record MarkContext(int Number, string? Sample, DateTimeOffset Now, string Profile);

/// <summary>
/// A mark's text with placeholders: <c>{n}</c> or <c>{n:000}</c> (the number, zero-padded to as many digits as zeros),
/// <c>{sample}</c>, <c>{date}</c> (yyyy-MM-dd), <c>{time}</c> (HH:mm) and <c>{profile}</c>; <c>{{</c> and <c>}}</c> are braces.
/// </summary>
public static partial class MarkText
{
    /// <summary>The placeholders, for help texts.</summary>
    public const string Placeholders = "{n}, {n:000}, {sample}, {date}, {time}, {profile}";

    /// <summary>The text for one copy.</summary>
    /// <exception cref="MarkException">An unknown or unclosed placeholder, or {sample} with no sample given.</exception>
    public static string Resolve(string template, MarkContext context)
    {
        ArgumentNullException.ThrowIfNull(template);
        ArgumentNullException.ThrowIfNull(context);
        var output = new StringBuilder();
        for (var i = 0; i < template.Length; i++)
        {
            var c = template[i];
            if (c == '}' )
            {
                if (i + 1 < template.Length && template[i + 1] == '}')
                {
                    output.Append('}');
                    i++;
                    continue;
                }

                throw new MarkException($"\"{template}\": a lone '}}' (write }}}} for a brace)");
            }

            if (c != '{')
            {
                output.Append(c);
                continue;
            }

            if (i + 1 < template.Length && template[i + 1] == '{')
            {
                output.Append('{');
                i++;
                continue;
            }

            var end = template.IndexOf('}', i + 1);
            if (end < 0)
            {
                throw new MarkException($"\"{template}\": a '{{' is not closed (placeholders: {Placeholders})");
            }

            output.Append(Value(template, template[(i + 1)..end], context));
            i = end;
        }

        return output.ToString();
    }

    /// <summary>Whether <paramref name="template"/> names a placeholder whose value changes from copy to copy or run to run.</summary>
    public static bool HasPlaceholders(string template) => template.Replace("{{", string.Empty, StringComparison.Ordinal).Contains('{', StringComparison.Ordinal);

    private static string Value(string template, string name, MarkContext context)
    {
        switch (name)
        {
            case "n":
                return context.Number.ToString(CultureInfo.InvariantCulture);
            case "sample":
                return context.Sample is { Length: > 0 } sample
                    ? sample
                    : throw new MarkException($"\"{template}\": {{sample}} needs the run's sample ID (--sample)");
            case "date":
                return context.Now.ToString("yyyy-MM-dd", CultureInfo.InvariantCulture);
            case "time":
                return context.Now.ToString("HH:mm", CultureInfo.InvariantCulture);
            case "profile":
                return context.Profile;
        }

        if (NumberFormat().Match(name) is { Success: true } match)
        {
            return context.Number.ToString(new string('0', match.Groups[1].Length), CultureInfo.InvariantCulture);
        }

        throw new MarkException($"\"{template}\": unknown placeholder {{{name}}} (placeholders: {Placeholders})");
    }

    [GeneratedRegex("^n:(0{1,9})$")]
    private static partial Regex NumberFormat();
}
