using System.Reflection;
using LaserEngrave.App.Services;
using LaserEngrave.App.ViewModels;
using Microsoft.Extensions.FileProviders;

namespace LaserEngrave.App.Web;

/// <summary>The composition root: the services, the view-models over them, the page and its API on one local web server.</summary>
public static class AppHost
{
    /// <summary>The header every POST must carry: a page of another site cannot add it without the server's consent (CORS).</summary>
    public const string RequestHeader = "X-LaserEngrave";

    /// <summary>Builds the app; <paramref name="configure"/> may replace services (tests give fakes or a data folder).</summary>
    public static WebApplication Build(string[] args, string? url = null, Action<IServiceCollection>? configure = null)
    {
        var builder = WebApplication.CreateBuilder(new WebApplicationOptions { Args = args, ContentRootPath = AppContext.BaseDirectory });
        builder.Logging.SetMinimumLevel(LogLevel.Warning);
        if (url is not null)
        {
            builder.WebHost.UseUrls(url);
        }

        var services = builder.Services;
        services.AddSingleton(AppFolders.Default);
        services.AddSingleton(TimeProvider.System);
        services.AddSingleton<MachineActivity>();
        services.AddSingleton<IImageService, ImageService>();
        services.AddSingleton<IMachineConnectionFactory>(new MachineConnectionFactory());
        services.AddSingleton<IRunService, ExecutorRunService>();
        services.AddSingleton<IFileAccess>(sp => new Services.FileAccess(sp.GetRequiredService<AppFolders>()));
        services.AddSingleton<ISettingsStore>(sp => new JsonSettingsStore(sp.GetRequiredService<AppFolders>().SettingsFile));
        services.AddSingleton<IRunLogStore>(sp => new RunLogFolder(sp.GetRequiredService<AppFolders>().RunLogFolder));
        services.AddSingleton(sp =>
        {
            var main = ActivatorUtilities.CreateInstance<MainViewModel>(sp);
            main.Restore();
            return main;
        });
        configure?.Invoke(services);

        var app = builder.Build();
        app.Use(GuardAsync);
        var page = new EmbeddedFileProvider(Assembly.GetExecutingAssembly(), "LaserEngrave.App.wwwroot");
        app.UseDefaultFiles(new DefaultFilesOptions { FileProvider = page });
        app.UseStaticFiles(new StaticFileOptions { FileProvider = page });
        ApiEndpoints.Map(app);
        app.Lifetime.ApplicationStopping.Register(() => Shutdown(app.Services));
        return app;
    }

    /// <summary>Refuses other hosts (DNS rebinding) and POSTs without the app's header (other sites' pages).</summary>
    private static Task GuardAsync(HttpContext context, RequestDelegate next)
    {
        var host = context.Request.Host.Host;
        if (host is not ("127.0.0.1" or "localhost" or "[::1]" or "::1"))
        {
            context.Response.StatusCode = StatusCodes.Status403Forbidden;
            return Task.CompletedTask;
        }

        if (HttpMethods.IsPost(context.Request.Method) && !context.Request.Headers.ContainsKey(RequestHeader))
        {
            context.Response.StatusCode = StatusCodes.Status403Forbidden;
            return context.Response.WriteAsync($"POST needs the {RequestHeader} header");
        }

        return next(context);
    }

    /// <summary>How long the exit waits for an aborted run to write its log before the ports are closed regardless.</summary>
    internal static readonly TimeSpan RunEndWait = TimeSpan.FromMilliseconds(1000);

    /// <summary>On exit the laser goes off and the ports close, whatever was running; an aborted run writes its log first.</summary>
    private static void Shutdown(IServiceProvider services)
    {
        var main = services.GetRequiredService<MainViewModel>();
        main.Run.AbortCommand.Execute(null);
        main.Activity.CancelCurrent();
        // The run's abort switches the laser off first, then the run writes its log; wait for that, but not for ever.
        _ = main.Activity.WhenIdleAsync().Wait(RunEndWait);
        if (main.Machine.Connection is { } connection)
        {
            try
            {
                connection.Gate.OffAsync(CancellationToken.None).WaitAsync(TimeSpan.FromMilliseconds(500)).GetAwaiter().GetResult();
            }
            catch (Exception ex) when (ex is TimeoutException or Devices.Abstractions.DeviceException or ObjectDisposedException or InvalidOperationException)
            {
                // Nothing more can be done at exit; the gate's watchdog switches the laser off by itself.
            }

            _ = main.Machine.CloseAsync().Wait(TimeSpan.FromMilliseconds(300));
        }
    }
}
