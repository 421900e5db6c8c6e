using System.Text.Json;
using LaserEngrave.App.ViewModels;

namespace LaserEngrave.App.Web;

/// <summary>Server-Sent Events: the state, sampled ten times a second and sent only when it changed.</summary>
/// <remarks>Sampling (not forwarding each change) caps the page's work at 10 Hz however fast the serial replies come.</remarks>
internal static class EventStream
{
    public static readonly TimeSpan Period = TimeSpan.FromMilliseconds(100);

    /// <remarks>The stream ends when the page goes away or the app stops, so an open page never holds the exit.</remarks>
    public static async Task SendAsync(HttpContext context, MainViewModel main, IHostApplicationLifetime lifetime)
    {
        context.Response.Headers.ContentType = "text/event-stream";
        context.Response.Headers.CacheControl = "no-cache";
        using var ended = CancellationTokenSource.CreateLinkedTokenSource(context.RequestAborted, lifetime.ApplicationStopping);
        var cancellationToken = ended.Token;
        string? last = null;
        using var timer = new PeriodicTimer(Period);
        try
        {
            do
            {
                var json = JsonSerializer.Serialize(StateSnapshot.From(main), JsonSerializerOptions.Web);
                if (json != last)
                {
                    await context.Response.WriteAsync($"data: {json}\n\n", cancellationToken).ConfigureAwait(false);
                    await context.Response.Body.FlushAsync(cancellationToken).ConfigureAwait(false);
                    last = json;
                }
            }
            while (await timer.WaitForNextTickAsync(cancellationToken).ConfigureAwait(false));
        }
        catch (OperationCanceledException)
        {
            // The page went away, or the app is stopping.
        }
    }
}
