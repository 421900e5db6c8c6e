using System.Text.Json;

namespace LaserEngrave.Core.IO;

/// <summary>What a JSON reader's refusal means in the file's own words: the field and the rule, never a .NET type name.</summary>
public static class JsonProblem
{
    /// <summary>One line "not a WHAT: FIELD ..." for <paramref name="ex"/>; <paramref name="what"/> names the kind of file ("run log").</summary>
    public static string Describe(JsonException ex, string what)
    {
        ArgumentNullException.ThrowIfNull(ex);
        var field = ex.Path is { Length: > 0 } path ? path.TrimStart('$').TrimStart('.') : string.Empty;
        var line = ex.LineNumber is { } n ? $" (line {n + 1})" : string.Empty;
        var message = ex.Message;
        var including = message.IndexOf("including:", StringComparison.Ordinal);
        var detail =
            including >= 0 ? $"a required field is missing: {message[(including + "including:".Length)..].Trim().TrimEnd('.')}"
            : message.Contains("null values", StringComparison.Ordinal) ? $"{Or(field)} must not be null{line}"
            : message.Contains("could not be converted", StringComparison.Ordinal) ? $"{Or(field)} has a value of the wrong type or out of range for it{line}"
            : $"not valid JSON{(field.Length > 0 ? $" at {field}" : string.Empty)}{line}";
        return $"not a {what}: {detail}";
    }

    private static string Or(string field) => field.Length > 0 ? field : "the whole file";
}
