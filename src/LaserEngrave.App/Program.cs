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
    // Read before the server starts, so a bad file is one line and exit 2, as on the command line.
    var simulator = options.SimulatorOptionsFile is { } simulatorFile
        ? LaserEngrave.Simulator.SimulatorOptionsFile.Load(simulatorFile, MachineConnectionFactory.DefaultSimulatorOptions)
        : null;
    app = AppHost.Build([.. options.HostArgs], options.Url, services =>
    {
        if (simulator is not null)
        {
            services.AddSingleton<IMachineConnectionFactory>(new MachineConnectionFactory(simulator));
        }

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
catch (Exception ex) when (ex is ArgumentException or InvalidDataException)
{
    Console.Error.WriteLine(ex.Message);
    return 2;
}

try
{
    await app.StartAsync();
}
catch (Exception ex) when (ex is IOException or System.Net.Sockets.SocketException)
{
    // A port in use, or an address this computer cannot bind: one line, as for a refused option.
    Console.Error.WriteLine(ex is IOException ? ex.Message : $"cannot listen on {options.Url ?? "the configured address"}: {ex.Message}");
    return 2;
}

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
var launchCodes = app.Services.GetRequiredService<LaunchCodes>();
var address = addresses.First().TrimEnd('/');
var folders = app.Services.GetRequiredService<AppFolders>();
var connectionFile = folders.ConnectionFile;
try
{
    // For scripts of the same user (clients/python): the address, token and process id, readable by the user alone.
    ConnectionFile.Write(connectionFile, address, token.Value, Environment.ProcessId);
    app.Lifetime.ApplicationStopping.Register(() => ConnectionFile.Remove(connectionFile, token.Value));
}
catch (Exception ex) when (ex is IOException or UnauthorizedAccessException)
{
    Console.Error.WriteLine($"{connectionFile}: could not write the address for scripts ({ex.Message}); they cannot find the app");
}

// Created now, so the window's connections are counted from the first.
_ = app.Services.GetRequiredService<WindowLifetime>();
var opened = false;
if (options.OpenBrowser)
{
    try
    {
        // The browser is given a file readable by the user alone that sends it on with a launch code of its own: its
        // command line (which every local user can read) names only the file.
        var launchFile = launchCodes.WriteLaunchFile(folders.LaunchFolder, address);
        opened = BrowserLauncher.TryOpen(launchFile, Path.Combine(folders.DataFolder, "window"));
    }
    catch (Exception ex) when (ex is IOException or UnauthorizedAccessException)
    {
        Console.Error.WriteLine($"{folders.LaunchFolder}: could not write the window's launch file ({ex.Message})");
    }
}

// Printed once the connection file is there, so whoever reads this line finds it. With no window of its own the
// address carries a one-time launch code, never the token: opened once by hand, it is refused afterwards. With its
// window open it carries none, so a line kept in a log opens nothing.
Console.WriteLine(opened
    ? $"LaserEngrave is running at {address} (in its own window)"
    : $"LaserEngrave is running at {address}/#{LaunchCodes.FragmentName}={launchCodes.Issue()}");
Console.WriteLine("Ctrl+C stops it (the laser is switched off first).");
if (options.OpenBrowser && !opened)
{
    Console.WriteLine("Could not open a browser: open the address above yourself (it works once).");
}

await app.WaitForShutdownAsync();
return 0;
