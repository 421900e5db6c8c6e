using System.Text;
using System.Text.Json;
using System.Text.Json.Serialization;
using Microsoft.AspNetCore.Http.Json;

namespace LaserEngrave.App.Web;

/// <summary>
/// How the API reads a request body: at most <see cref="MaxJsonBytes"/>, bound to a record whose members are all
/// required unless they have a default, every number finite, every name one the API knows; a refusal is 400 with one
/// line that quotes at most <see cref="QuoteLength"/> characters of what was sent.
/// </summary>
internal static class ApiRequests
{
    /// <summary>The largest JSON body any route takes: the longest (a job edit with every field, notes) is a few hundred bytes.</summary>
    public const int MaxJsonBytes = 64 * 1024;

    /// <summary>The most characters of a sent value an answer repeats (the state repeats answers to every page).</summary>
    public const int QuoteLength = 40;

    /// <summary>The route that takes a file's bytes, under the upload limit instead.</summary>
    private const string UploadPath = "/api/image";

    /// <summary>The API's JSON: missing members, unknown members and nulls refused, no number from a string.</summary>
    public static void Configure(IServiceCollection services)
    {
        services.Configure<JsonOptions>(o => Configure(o.SerializerOptions));

        // A body that cannot be bound reaches ReadAsync as an exception with the reader's reason, not as an empty 400.
        services.Configure<RouteHandlerOptions>(o => o.ThrowOnBadRequest = true);
    }

    public static void Configure(JsonSerializerOptions options)
    {
        ArgumentNullException.ThrowIfNull(options);
        options.RespectRequiredConstructorParameters = true;
        options.RespectNullableAnnotations = true;
        options.UnmappedMemberHandling = JsonUnmappedMemberHandling.Disallow;

        // A number is a JSON number: never "5" nor "NaN" (a number too large for a double, 1e309, is refused by the request's check).
        options.NumberHandling = JsonNumberHandling.Strict;
    }

    /// <summary>
    /// How states are written: a value that is not finite (which no request can set, but a view-model might hold) is
    /// written as "NaN" or "Infinity" instead of failing every state answer after it.
    /// </summary>
    public static readonly JsonSerializerOptions StateJson = new(JsonSerializerDefaults.Web) { NumberHandling = JsonNumberHandling.AllowNamedFloatingPointLiterals };

    /// <summary>
    /// Middleware for /api: a JSON body larger than <see cref="MaxJsonBytes"/> is refused (413) before it is read into
    /// anything, and a body the route cannot bind is 400 with the reason in a line.
    /// </summary>
    public static async Task ReadAsync(HttpContext context, RequestDelegate next)
    {
        ArgumentNullException.ThrowIfNull(context);
        ArgumentNullException.ThrowIfNull(next);
        var request = context.Request;
        if (!request.Path.StartsWithSegments("/api", StringComparison.Ordinal))
        {
            await next(context).ConfigureAwait(false);
            return;
        }

        if (!HttpMethods.IsGet(request.Method) && !request.Path.Equals(UploadPath, StringComparison.Ordinal) && !await HoldBodyAsync(context).ConfigureAwait(false))
        {
            return;
        }

        try
        {
            await next(context).ConfigureAwait(false);
        }
        catch (BadHttpRequestException ex) when (!context.Response.HasStarted)
        {
            await RefuseAsync(context, StatusCodes.Status400BadRequest, Describe(ex)).ConfigureAwait(false);
        }
    }

    /// <summary>Reads the body whole (it is small), so one without a length is held to the same limit; false when refused.</summary>
    private static async Task<bool> HoldBodyAsync(HttpContext context)
    {
        var request = context.Request;
        if (request.ContentLength is > MaxJsonBytes)
        {
            await RefuseAsync(context, StatusCodes.Status413PayloadTooLarge, TooLarge(request.ContentLength.Value)).ConfigureAwait(false);
            return false;
        }

        var buffer = new MemoryStream();
        var chunk = new byte[8192];
        int read;
        while ((read = await request.Body.ReadAsync(chunk, context.RequestAborted).ConfigureAwait(false)) > 0)
        {
            buffer.Write(chunk, 0, read);
            if (buffer.Length > MaxJsonBytes)
            {
                await RefuseAsync(context, StatusCodes.Status413PayloadTooLarge, TooLarge(null)).ConfigureAwait(false);
                return false;
            }
        }

        buffer.Position = 0;
        request.Body = buffer;
        return true;
    }

    /// <summary>Endpoint filter: a bound request whose values are unusable is 400 with its line, before the route runs.</summary>
    public static ValueTask<object?> CheckAsync(EndpointFilterInvocationContext context, EndpointFilterDelegate next)
    {
        ArgumentNullException.ThrowIfNull(context);
        ArgumentNullException.ThrowIfNull(next);
        foreach (var argument in context.Arguments)
        {
            if (argument is IApiRequest request && request.Problem() is { } problem)
            {
                return ValueTask.FromResult<object?>(Results.Json(new { error = problem }, statusCode: StatusCodes.Status400BadRequest));
            }
        }

        return next(context);
    }

    /// <summary>The refusal's line for a body the route could not bind: the field and what is wrong, never the .NET reader's text.</summary>
    public static string Describe(BadHttpRequestException ex)
    {
        ArgumentNullException.ThrowIfNull(ex);
        if (ex.InnerException is not JsonException json)
        {
            // The binder's own lines name the parameter in quotes with its type first: Required parameter "string path" was not provided.
            var named = ex.Message.Split('"') is { Length: > 2 } parts ? Quote(parts[1].Split(' ')[^1]) : null;
            return ex.Message.Contains("Content-Type", StringComparison.Ordinal) || ex.Message.Contains("body was inferred", StringComparison.Ordinal)
                ? "the request needs a JSON body (Content-Type: application/json)"
                : ex.Message.Contains("was not provided", StringComparison.Ordinal) && named is not null ? $"the request lacks {named} (docs/api.md)"
                : ex.Message.Contains("Failed to bind", StringComparison.Ordinal) && named is not null ? $"{named} has a value of the wrong type"
                : "the request could not be read: check it against docs/api.md";
        }

        var field = json.Path is { Length: > 1 } path ? Quote(path.TrimStart('$').TrimStart('.')) : null;
        var message = json.Message;
        if (message.Contains("missing required properties", StringComparison.Ordinal) || message.Contains("missing required", StringComparison.Ordinal))
        {
            var names = message.IndexOf("including:", StringComparison.Ordinal) is var i and >= 0 ? message[(i + "including:".Length)..].Trim().TrimEnd('.') : "?";
            return $"the request lacks {Quote(names)}: send every field the route takes (docs/api.md)";
        }

        if (message.Contains("could not be mapped", StringComparison.Ordinal))
        {
            var name = message.Split('\'') is { Length: > 2 } parts ? parts[1] : field ?? "?";
            return $"'{Quote(name)}' is not a field of this request (docs/api.md lists them)";
        }

        if (field is null && message.Contains("could not be converted", StringComparison.Ordinal))
        {
            return "the request body must be a JSON object, like {\"path\": \"...\"} (docs/api.md shows each route's)";
        }

        if (message.Contains("null", StringComparison.OrdinalIgnoreCase) && field is not null)
        {
            return $"{field} must not be null";
        }

        return field is not null
            ? $"{field} has a value of the wrong type (a number where a number is meant, true or false, or text in quotes)"
            : $"the request body is not valid JSON{(json.LineNumber is { } line ? $" (line {line + 1}, column {json.BytePositionInLine + 1})" : string.Empty)}";
    }

    /// <summary>At most <see cref="QuoteLength"/> characters of what was sent, marked when cut, without control characters.</summary>
    public static string Quote(string? text)
    {
        if (text is null)
        {
            return "null";
        }

        var cut = text.Length > QuoteLength ? text[..QuoteLength] : text;
        var clean = new StringBuilder(cut.Length + 1);
        foreach (var c in cut)
        {
            clean.Append(char.IsControl(c) ? '?' : c);
        }

        return text.Length > QuoteLength ? $"{clean}… ({text.Length} characters)" : clean.ToString();
    }

    /// <summary>The problem with a number sent for <paramref name="field"/>, or null when it is a finite number.</summary>
    public static string? Finite(string field, double? value) =>
        value is { } v && !double.IsFinite(v) ? $"{field} must be a finite number (got {v.ToString(System.Globalization.CultureInfo.InvariantCulture)})" : null;

    private static string TooLarge(long? length) =>
        $"the request body is {(length is { } n ? $"{n} bytes, " : string.Empty)}more than the {MaxJsonBytes / 1024} KB a JSON request may have";

    private static Task RefuseAsync(HttpContext context, int status, string error)
    {
        context.Response.StatusCode = status;
        return context.Response.WriteAsJsonAsync(new { error }, context.RequestAborted);
    }
}

/// <summary>A request body that checks its own values once bound (finite numbers, known names); null when usable.</summary>
internal interface IApiRequest
{
    string? Problem();
}
