using System.Net;

namespace LaserEngrave.App.Web;

/// <summary>The app listens on this computer only: every address it is configured with must be a loopback address.</summary>
/// <remarks>
/// Checked for each way ASP.NET Core takes addresses: --urls (the app's own or <c>--urls=</c>), ASPNETCORE_URLS,
/// "urls" and "Kestrel:Endpoints" in appsettings, and ASPNETCORE_HTTP(S)_PORTS (which mean every interface).
/// </remarks>
public static class LoopbackAddresses
{
    /// <summary>One line naming the first address that is not on this computer; null when all are.</summary>
    public static string? Problem(IConfiguration configuration, string urls)
    {
        ArgumentNullException.ThrowIfNull(configuration);
        ArgumentNullException.ThrowIfNull(urls);
        foreach (var url in Split(urls))
        {
            if (!IsLoopback(url))
            {
                return Refusal(url, "--urls");
            }

            if (IsIPv4Mapped(url))
            {
                return $"{url} (--urls) is an IPv4 address written as IPv6, which the server cannot listen on: write it as IPv4, e.g. --urls http://127.0.0.1:5080";
            }

            if (NotHttp(url))
            {
                return HttpOnly(url, "--urls");
            }
        }

        foreach (var endpoint in configuration.GetSection("Kestrel:Endpoints").GetChildren())
        {
            if (endpoint["Url"] is { } url && !IsLoopback(url))
            {
                return Refusal(url, $"Kestrel:Endpoints:{endpoint.Key}:Url");
            }

            if (endpoint["Url"] is { } other && NotHttp(other))
            {
                return HttpOnly(other, $"Kestrel:Endpoints:{endpoint.Key}:Url");
            }
        }

        return null;
    }

    /// <summary>Whether <paramref name="url"/> names 127.0.0.0/8, ::1 or localhost; wildcards (*, +, 0.0.0.0, ::) and names are not.</summary>
    public static bool IsLoopback(string url)
    {
        ArgumentNullException.ThrowIfNull(url);
        var host = HostOf(url.Trim());
        if (host is null)
        {
            return false;
        }

        if (string.Equals(host, "localhost", StringComparison.OrdinalIgnoreCase))
        {
            return true;
        }

        return IPAddress.TryParse(host.Trim('[', ']'), out var address) && IPAddress.IsLoopback(address);
    }

    /// <summary>Whether <paramref name="url"/>'s host is an IPv4-mapped IPv6 address ([::ffff:127.0.0.1]): loopback, but no socket binds it.</summary>
    private static bool IsIPv4Mapped(string url) =>
        HostOf(url.Trim()) is { } host && IPAddress.TryParse(host.Trim('[', ']'), out var address) && address.IsIPv4MappedToIPv6;

    public static IEnumerable<string> Split(string urls) =>
        urls.Split(';', StringSplitOptions.RemoveEmptyEntries | StringSplitOptions.TrimEntries);

    private static string? HostOf(string url)
    {
        var scheme = url.IndexOf("://", StringComparison.Ordinal);
        if (scheme < 0)
        {
            return null;
        }

        var rest = url[(scheme + 3)..];
        var end = rest.IndexOf('/', StringComparison.Ordinal);
        var authority = end < 0 ? rest : rest[..end];
        if (authority.StartsWith('['))
        {
            var close = authority.IndexOf(']', StringComparison.Ordinal);
            return close < 0 ? null : authority[..(close + 1)];
        }

        var colon = authority.LastIndexOf(':');
        return colon < 0 ? authority : authority[..colon];
    }

    /// <summary>Whether <paramref name="url"/> is anything but http:// (https needs a certificate the app never sets up, and the server would not start).</summary>
    private static bool NotHttp(string url) => !url.Trim().StartsWith("http://", StringComparison.OrdinalIgnoreCase);

    private static string HttpOnly(string url, string source) =>
        $"{url} ({source}): the app listens over http:// only (on this computer alone https adds nothing but a certificate to set up), e.g. --urls http://127.0.0.1:5080";

    private static string Refusal(string url, string source) =>
        $"{url} ({source}) is not an address of this computer: the app listens on loopback only (127.0.0.1, [::1] or localhost), e.g. --urls http://127.0.0.1:5080";
}
