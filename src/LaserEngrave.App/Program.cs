using LaserEngrave.App.Services;
using LaserEngrave.App.Web;
using Microsoft.AspNetCore.Hosting.Server;
using Microsoft.AspNetCore.Hosting.Server.Features;

if (args.Any(a => a is "--help" or "-h"))
{
    Console.WriteLine(AppOptions.Usage);
    return 0;
}

AppOptions options;
WebApplication app;
try
{
    options = AppOptions.Parse(args);
    app = AppHost.Build([.. options.HostArgs], options.Url, services =>
    {
        if (options.DataFolder is { } folder)
        {
            services.AddSingleton(new AppFolders(Path.GetFullPath(folder)));
        }

        if (options.OpenBrowser)
        {
            // The app's own window: closing it ends the app (after the grace period, never during a run).
            services.AddSingleton(new WindowLifetimeOptions(options.IdleExit));
        }
    });
}
catch (ArgumentException ex)
{
    Console.Error.WriteLine(ex.Message);
    return 2;
}

await app.StartAsync();

// Ctrl+C, SIGQUIT and SIGTERM stop the host (its console lifetime); a hang-up (SIGHUP: a closed terminal or a dropped
// remote session; on Windows the console window closed) does the same: a run aborts, laser off first, and writes its log.
using var hangUp = AppHost.StopOnHangUp(app.Lifetime);
var addresses = app.Services.GetRequiredService<IServer>().Features.Get<IServerAddressesFeature>()!.Addresses;
if (addresses.FirstOrDefault(a => !LoopbackAddresses.IsLoopback(a)) is { } open)
{
    // Configuration the checks before the start did not see: never stay open to the network.
    Console.Error.WriteLine($"{open} is not an address of this computer: the app listens on loopback only");
    await app.StopAsync();
    return 2;
}

var token = app.Services.GetRequiredService<AccessToken>();
var url = $"{addresses.First().TrimEnd('/')}/?{AccessToken.QueryName}={token.Value}";
Console.WriteLine($"LaserEngrave is running at {url}");
Console.WriteLine("Ctrl+C stops it (the laser is switched off first).");
// Created now, so the window's connections are counted from the first.
_ = app.Services.GetRequiredService<WindowLifetime>();
var profileFolder = Path.Combine(app.Services.GetRequiredService<AppFolders>().DataFolder, "window");
if (options.OpenBrowser && !BrowserLauncher.TryOpen(url, profileFolder))
{
    Console.WriteLine("Could not open a browser: open the address above yourself.");
}

await app.WaitForShutdownAsync();
return 0;
