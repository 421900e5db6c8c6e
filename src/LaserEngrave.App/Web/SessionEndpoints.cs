using System.Security.Cryptography;
using System.Text;

namespace LaserEngrave.App.Web;

/// <summary>
/// The two routes that take no token: the page trades its one-time launch code for the token (<c>POST /api/session</c>),
/// and a script asks the server on the port to prove it holds the token before it sends it (<c>GET /api/proof</c>).
/// </summary>
internal static class SessionEndpoints
{
    public const string SessionPath = "/api/session";

    public const string ProofPath = "/api/proof";

    /// <summary>What the proof's HMAC is taken over, before the challenge: the proof answers this question and no other.</summary>
    public const string ProofPrefix = "laserengrave-proof:";

    /// <summary>A challenge is a nonce: 16 to 128 URL-safe characters (a longer text would only make the server hash more).</summary>
    private const int MinChallenge = 16;
    private const int MaxChallenge = 128;

    public static void Map(IEndpointRouteBuilder app)
    {
        app.MapPost(SessionPath, (HttpContext context, LaunchCodes codes, AccessToken token) =>
        {
            // Never cached, never stored: the answer is the token itself.
            context.Response.Headers.CacheControl = "no-store";
            return codes.Redeem(context.Request.Headers[LaunchCodes.HeaderName].ToString())
                ? Results.Json(new SessionAnswer(token.Value))
                : Results.Text("this launch code is not valid or was used already: open the app from the window it opened or from the address it printed at start (each works once)", statusCode: StatusCodes.Status401Unauthorized);
        })
            .WithSummary("The page's first request: its one-time launch code (header X-LaserEngrave-Launch) traded for the start's token; 401 for a code unknown or used.")
            .Produces<SessionAnswer>()
            .Produces<string>(StatusCodes.Status401Unauthorized, "text/plain");

        app.MapGet(ProofPath, (string? challenge, AccessToken token) =>
            challenge is { Length: >= MinChallenge and <= MaxChallenge } && challenge.All(c => char.IsAsciiLetterOrDigit(c) || c is '-' or '_')
                ? Results.Json(new ProofAnswer("LaserEngrave", Environment.ProcessId, Proof(token.Value, challenge)))
                : Results.Text($"challenge: {MinChallenge} to {MaxChallenge} letters, digits, '-' or '_'", statusCode: StatusCodes.Status400BadRequest))
            .WithSummary("Before a script sends the token: HMAC-SHA256 keyed by the token over 'laserengrave-proof:' + challenge (lowercase hex), and the app's process id, so the script knows the server on the port is this start of the app.")
            .Produces<ProofAnswer>()
            .Produces<string>(StatusCodes.Status400BadRequest, "text/plain");
    }

    /// <summary>HMAC-SHA256 keyed by the token's text over <see cref="ProofPrefix"/> + <paramref name="challenge"/>, lowercase hex.</summary>
    public static string Proof(string token, string challenge) =>
        Convert.ToHexStringLower(HMACSHA256.HashData(Encoding.ASCII.GetBytes(token), Encoding.ASCII.GetBytes(ProofPrefix + challenge)));

    /// <summary>Whether a request is for one of these routes (the guard lets them through without the token).</summary>
    public static bool IsSessionRoute(HttpRequest request) =>
        (HttpMethods.IsPost(request.Method) && request.Path.Equals(SessionPath, StringComparison.OrdinalIgnoreCase))
        || (HttpMethods.IsGet(request.Method) && request.Path.Equals(ProofPath, StringComparison.OrdinalIgnoreCase));

    /// <param name="Token">The start's token, for the page to keep in its tab.</param>
    public sealed record SessionAnswer(string Token);

    /// <param name="App">Always "LaserEngrave".</param>
    /// <param name="Pid">The app's process id (connection.json names the same).</param>
    /// <param name="Proof">HMAC-SHA256(token, "laserengrave-proof:" + challenge), lowercase hex.</param>
    public sealed record ProofAnswer(string App, int Pid, string Proof);
}
