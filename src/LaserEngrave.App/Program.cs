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
try
{
    options = AppOptions.Parse(args);
}
catch (ArgumentException ex)
{
    Console.Error.WriteLine(ex.Message);
    return 2;
}

var app = AppHost.Build([.. options.HostArgs], options.Url, services =>
{
    if (options.DataFolder is { } folder)
    {
        services.AddSingleton(new AppFolders(Path.GetFullPath(folder)));
    }
});
await app.StartAsync();
var url = app.Services.GetRequiredService<IServer>().Features.Get<IServerAddressesFeature>()!.Addresses.First();
Console.WriteLine($"LaserEngrave is running at {url}  (Ctrl+C to stop)");
if (options.OpenBrowser && !BrowserLauncher.TryOpen(url))
{
    Console.WriteLine("Could not open a browser: open the address above yourself.");
}

await app.WaitForShutdownAsync();
return 0;
