using System.Security.Cryptography;
using System.Text;

namespace LaserEngrave.App.Web;

/// <summary>
/// The secret made at each start that the page and every API call must show. It is on no command line and in no
/// address: the page gets it by trading a one-time launch code (<see cref="LaunchCodes"/>), scripts read it from
/// connection.json (readable by the user alone), so another local user or a page of another site cannot drive the laser.
/// </summary>
public sealed class AccessToken
{
    /// <summary>The header automation can send instead of <c>Authorization: Bearer</c>.</summary>
    public const string HeaderName = "X-LaserEngrave-Token";

    /// <summary>Where earlier versions put the token in the page's address: refused now, whatever it carries.</summary>
    public const string QueryName = "token";

    /// <summary>Where SignalR's browser client puts the token on a WebSocket, which cannot carry a header; taken on the hub only.</summary>
    public const string HubQueryName = "access_token";

    private readonly byte[] _bytes;

    /// <summary>256 random bits from the system's cryptographic generator, as URL-safe text.</summary>
    public AccessToken()
        : this(Convert.ToBase64String(RandomNumberGenerator.GetBytes(32)).TrimEnd('=').Replace('+', '-').Replace('/', '_'))
    {
    }

    internal AccessToken(string value)
    {
        Value = value;
        _bytes = Encoding.ASCII.GetBytes(value);
    }

    public string Value { get; }

    /// <summary>Compares in constant time, so the answer's timing tells nothing about the secret.</summary>
    public bool Matches(string? candidate) =>
        candidate is not null && CryptographicOperations.FixedTimeEquals(Encoding.ASCII.GetBytes(candidate), _bytes);

    /// <summary>
    /// Whether a request shows the token in <c>Authorization: Bearer</c> or the <see cref="HeaderName"/> header; on the
    /// page's hub (<paramref name="hub"/>) also in <see cref="HubQueryName"/>. Never a cookie: a browser sends cookies by
    /// itself, to every port on 127.0.0.1.
    /// </summary>
    internal bool IsShownBy(HttpRequest request, bool hub)
    {
        var authorization = request.Headers.Authorization.ToString();
        if (authorization.StartsWith("Bearer ", StringComparison.OrdinalIgnoreCase) && Matches(authorization["Bearer ".Length..].Trim()))
        {
            return true;
        }

        return Matches(request.Headers[HeaderName].ToString())
            || (hub && request.Query.TryGetValue(HubQueryName, out var query) && Matches(query.ToString()));
    }
}
