using System.Globalization;
using System.Text.Json;
using LaserEngrave.Core.Input;

namespace LaserEngrave.Core.IO;

/// <summary>What a JSON reader's refusal means in the file's own words: the field, the rule and where (line and column from 1), never a .NET type name.</summary>
public static class JsonProblem
{
    /// <summary>One line "not a WHAT: FIELD ..." for <paramref name="ex"/>; <paramref name="what"/> names the kind of file ("run log").</summary>
    /// <param name="text">The file's text, when at hand: a number written as text ("12,5") is then named with how to write it.</param>
    public static string Describe(JsonException ex, string what, string? text = null)
    {
        ArgumentNullException.ThrowIfNull(ex);
        var field = Field(ex);
        var at = Position(ex) is { } position ? $" ({position})" : string.Empty;
        var message = ex.Message;
        var including = message.IndexOf("including:", StringComparison.Ordinal);
        var detail =
            including >= 0 ? $"a required field is missing: {message[(including + "including:".Length)..].Trim().TrimEnd('.')}"
            : message.Contains("null values", StringComparison.Ordinal) ? $"{Or(field)} must not be null{at}"
            : message.Contains("could not be converted", StringComparison.Ordinal) ? $"{Or(field)} has a value of the wrong type or out of range for it{at}{NumberHint(text, ex.Path)}"
            : Syntax(ex);
        return $"not a {what}: {detail}";
    }

    /// <summary>"not valid JSON at line 3, column 7: a comma is missing ..." for a file the JSON reader could not follow.</summary>
    public static string Syntax(JsonException ex)
    {
        ArgumentNullException.ThrowIfNull(ex);
        var at = Position(ex) is { } position ? $" at {position}" : Field(ex) is { Length: > 0 } field ? $" at {field}" : string.Empty;
        return $"not valid JSON{at}{(Reason(ex.Message) is { } reason ? $": {reason}" : string.Empty)}";
    }

    /// <summary>"line 3, column 7" (both from 1, as an editor counts) where the reader stopped; null when it did not say.</summary>
    public static string? Position(JsonException ex)
    {
        ArgumentNullException.ThrowIfNull(ex);
        return ex.LineNumber is { } line
            ? string.Create(CultureInfo.InvariantCulture, $"line {line + 1}{(ex.BytePositionInLine is { } column ? $", column {column + 1}" : string.Empty)}")
            : null;
    }

    /// <summary>
    /// How to write the value at <paramref name="path"/> when it is a number written as text: ", write 12.5 as a number,
    /// without quotes" for "12,5", both readings for "1,000"; empty when it is not one.
    /// </summary>
    public static string NumberHint(string? text, string? path)
    {
        if (text is null || path is null || ValueAt(text, path) is not { } value)
        {
            return string.Empty;
        }

        return Ambiguous(value) is { } readings ? $": \"{value}\" {readings}, as a number without quotes"
            : NumberText.TryParse(value, out var number, out _) ? $": write {NumberText.Show(number)} as a number, without quotes"
            : string.Empty;
    }

    /// <summary>The string at a reader's JSON path ($.gate.watchdogMs, $.scanOffsets[1].offsetUm) in <paramref name="text"/>; null when it is not a string.</summary>
    public static string? ValueAt(string text, string path)
    {
        ArgumentNullException.ThrowIfNull(text);
        ArgumentNullException.ThrowIfNull(path);
        try
        {
            using var document = JsonDocument.Parse(text, new JsonDocumentOptions { AllowTrailingCommas = true, CommentHandling = JsonCommentHandling.Skip });
            var element = document.RootElement;
            foreach (var step in Steps(path))
            {
                if (step is int index)
                {
                    if (element.ValueKind != JsonValueKind.Array || index >= element.GetArrayLength())
                    {
                        return null;
                    }

                    element = element[index];
                }
                else if (element.ValueKind != JsonValueKind.Object || !element.TryGetProperty((string)step, out element))
                {
                    return null;
                }
            }

            return element.ValueKind == JsonValueKind.String ? element.GetString() : null;
        }
        catch (JsonException)
        {
            return null;
        }
    }

    private static string? Ambiguous(string value) => NumberText.Ambiguous(value);

    /// <summary>The path's steps: property names and array indexes ($.a.b[2].c, $['odd name']).</summary>
    private static IEnumerable<object> Steps(string path)
    {
        var i = path.StartsWith('$') ? 1 : 0;
        while (i < path.Length)
        {
            if (path[i] == '.')
            {
                var end = path.IndexOfAny(['.', '['], i + 1);
                end = end < 0 ? path.Length : end;
                yield return path[(i + 1)..end];
                i = end;
            }
            else if (path[i] == '[' && i + 1 < path.Length && path[i + 1] == '\'')
            {
                var end = path.IndexOf("']", i + 2, StringComparison.Ordinal);
                if (end < 0)
                {
                    yield break;
                }

                yield return path[(i + 2)..end];
                i = end + 2;
            }
            else if (path[i] == '[')
            {
                var end = path.IndexOf(']', i);
                if (end < 0 || !int.TryParse(path.AsSpan(i + 1, end - i - 1), NumberStyles.None, CultureInfo.InvariantCulture, out var index))
                {
                    yield break;
                }

                yield return index;
                i = end + 1;
            }
            else
            {
                yield break;
            }
        }
    }

    /// <summary>The reader's complaint in a person's words; null when it is not one of the common ones.</summary>
    private static string? Reason(string message)
    {
        // The reader's messages begin with the character it met in quotes: "'x' is an invalid start of a value."
        var met = message.Length > 2 && message[0] == '\'' && message.IndexOf("' is", 1, StringComparison.Ordinal) is var close and > 0 ? message[1..close] : null;
        return message switch
        {
            _ when message.Contains("is an invalid start of a value", StringComparison.Ordinal) =>
                $"{Shown(met)} cannot begin a value (text goes in double quotes, a number has a decimal point, true and false are lower case)",
            _ when message.Contains("is invalid after a value", StringComparison.Ordinal) =>
                $"{Shown(met)} where a comma or a closing bracket belongs: a comma is missing before it, or a bracket is too many",
            _ when message.Contains("is invalid after a property name", StringComparison.Ordinal) =>
                "a colon (:) belongs after a field's name",
            _ when message.Contains("is invalid after a single JSON value", StringComparison.Ordinal) =>
                $"{Shown(met)} after the end: the file has more than one {{...}}, or a closing bracket too many",
            _ when message.Contains("is invalid within a JSON string", StringComparison.Ordinal) =>
                "a text in quotes holds a character it cannot (a tab or line break, or a backslash: write \\\\ for \\)",
            _ when message.Contains("does not contain any JSON tokens", StringComparison.Ordinal) =>
                "the file is empty",
            _ when message.Contains("Expected depth to be zero", StringComparison.Ordinal) || message.Contains("reached end of data", StringComparison.Ordinal) || message.Contains("end of the JSON payload", StringComparison.Ordinal) =>
                "the file ends before every { and [ is closed",
            _ when message.Contains("trailing comma", StringComparison.OrdinalIgnoreCase) =>
                "a comma before } or ] (remove it)",
            _ when message.Contains("Expected a value, but instead", StringComparison.Ordinal) || message.Contains("start of a property name", StringComparison.Ordinal) =>
                "a field's name goes in double quotes",
            _ when message.Contains("Comments are not allowed", StringComparison.Ordinal) =>
                "this file takes no comments",
            _ => null,
        };
    }

    private static string Shown(string? met) => met is null ? "a character" : met.Length == 1 && char.IsWhiteSpace(met[0]) ? "a space" : $"'{met}'";

    private static string Field(JsonException ex) => ex.Path is { Length: > 0 } path ? path.TrimStart('$').TrimStart('.') : string.Empty;

    private static string Or(string field) => field.Length > 0 ? field : "the whole file";
}
