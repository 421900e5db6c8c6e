namespace LaserEngrave.App.Web;

/// <summary>The app's own command-line options; everything else goes to ASP.NET Core.</summary>
/// <param name="OpenBrowser">Open the page in the default browser (off with --no-browser).</param>
/// <param name="Url">Where to listen (--urls, loopback addresses only); null for ASPNETCORE_URLS or appsettings' "urls", else a free port on 127.0.0.1.</param>
/// <param name="DataFolder">Where settings, images and logs go (--data-folder); by default the user's application-data folder.</param>
/// <param name="IdleExit">How long the app outlives its closed window (--idle-exit SECONDS); used only when it opened the window itself.</param>
public sealed record AppOptions(bool OpenBrowser, string? Url, string? DataFolder, TimeSpan IdleExit)
{
    /// <summary>The built-in simulator's options file (--sim-options FILE, as the CLI's): firmware, latency, faults, start position.</summary>
    public string? SimulatorOptionsFile { get; init; }

    public static readonly TimeSpan DefaultIdleExit = TimeSpan.FromSeconds(10);

    /// <summary>Options in ASP.NET Core's --key=value form, passed on to the host (test hosts set the content root this way).</summary>
    public IReadOnlyList<string> HostArgs { get; init; } = [];

    public const string DefaultUrl = "http://127.0.0.1:0";

    /// <summary>Reads --no-browser, --urls URL, --data-folder PATH, --sim-options FILE and --idle-exit SECONDS; throws <see cref="ArgumentException"/> with one line for a bad value.</summary>
    public static AppOptions Parse(IReadOnlyList<string> args)
    {
        ArgumentNullException.ThrowIfNull(args);
        var options = new AppOptions(true, null, null, DefaultIdleExit);
        for (var i = 0; i < args.Count; i++)
        {
            switch (args[i])
            {
                case "--no-browser":
                    options = options with { OpenBrowser = false };
                    break;
                case "--urls":
                    options = options with { Url = Value(i++) };
                    break;
                case "--data-folder":
                    options = options with { DataFolder = Value(i++) };
                    break;
                case "--sim-options":
                    options = options with { SimulatorOptionsFile = Value(i++) };
                    break;
                case "--idle-exit":
                    var text = Value(i++);
                    options = options with
                    {
                        IdleExit = Core.Input.NumberText.TryParse(text, out var seconds, out _) && seconds is >= 0 and <= 86400
                            ? TimeSpan.FromSeconds(seconds)
                            : throw new ArgumentException($"--idle-exit {text}: seconds from 0 to 86400"),
                    };
                    break;
                case "--help" or "-h":
                    throw new ArgumentException(Usage);
                case var hostArg when hostArg.StartsWith("--", StringComparison.Ordinal) && hostArg.Contains('=', StringComparison.Ordinal):
                    options = options with { HostArgs = [.. options.HostArgs, hostArg] };
                    break;
                default:
                    throw new ArgumentException($"unknown option '{args[i]}'\n{Usage}");
            }
        }

        if (options.Url is { } urls && LoopbackAddresses.Split(urls).FirstOrDefault(u => !LoopbackAddresses.IsLoopback(u)) is { } open)
        {
            throw new ArgumentException($"--urls {open}: not an address of this computer; the app listens on loopback only, e.g. http://127.0.0.1:5080");
        }

        return options;

        string Value(int at) => at + 1 < args.Count ? args[at + 1] : throw new ArgumentException($"{args[at]} needs a value");
    }

    public const string Usage = "usage: LaserEngrave.App [--no-browser] [--urls http://127.0.0.1:PORT] [--data-folder PATH] [--sim-options FILE] [--idle-exit SECONDS]\n" +
        "  the app opens its own window and ends SECONDS (default 10) after it is closed, unless a run is under way; with --no-browser it runs until stopped\n" +
        "  --sim-options FILE: the built-in simulator's options (firmware, latency, faults, start position; docs/simulator.md)";
}
