using LaserEngrave.App.Services;
using LaserEngrave.App.Web;
using LaserEngrave.Simulator;
using Microsoft.AspNetCore.Hosting;
using Microsoft.AspNetCore.Mvc.Testing;
using Microsoft.Extensions.DependencyInjection;

namespace LaserEngrave.App.Tests.Web;

/// <summary>The app in-process with its data in a temporary folder and the simulator in virtual time.</summary>
/// <param name="configure">More services to replace (e.g. a run service the test holds).</param>
internal sealed class AppFactory(Action<IServiceCollection>? configure = null) : WebApplicationFactory<Program>
{
    private readonly TestFiles.TempFolder _folder = TestFiles.NewFolder();

    public string DataFolder => _folder.Path;

    public HttpClient NewClient()
    {
        var client = CreateClient();
        client.DefaultRequestHeaders.Authorization = new("Bearer", Services.GetRequiredService<AccessToken>().Value);
        return client;
    }

    /// <summary>The services tests and screenshots use instead of the user's folders and the real-time simulator.</summary>
    public static void UseTestServices(IServiceCollection services, string dataFolder)
    {
        services.AddSingleton(new AppFolders(dataFolder));
        services.AddSingleton<IMachineConnectionFactory>(new MachineConnectionFactory(new SimulatorOptions()));
    }

    protected override void ConfigureWebHost(IWebHostBuilder builder) =>
        builder.ConfigureServices(services =>
        {
            UseTestServices(services, _folder.Path);
            configure?.Invoke(services);
        });

    protected override void Dispose(bool disposing)
    {
        base.Dispose(disposing);
        if (disposing)
        {
            _folder.Dispose();
        }
    }
}
