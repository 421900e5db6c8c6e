using LaserEngrave.App.Components;
using LaserEngrave.App.Services;
using LaserEngrave.App.ViewModels;
using Microsoft.FluentUI.AspNetCore.Components;

namespace LaserEngrave.App.Web;

/// <summary>The composition root: the services, the view-models over them, the page and its API on one local web server.</summary>
public static class AppHost
{
    /// <summary>The header every POST must carry: a page of another site cannot add it without the server's consent (CORS).</summary>
    public const string RequestHeader = "X-LaserEngrave";

    /// <summary>Builds the app; <paramref name="configure"/> may replace services (tests give fakes or a data folder).</summary>
    public static WebApplication Build(string[] args, string? url = null, Action<IServiceCollection>? configure = null)
    {
        var builder = WebApplication.CreateBuilder(new WebApplicationOptions { Args = args, ContentRootPath = AppContext.BaseDirectory, ApplicationName = typeof(AppHost).Assembly.GetName().Name });
        builder.Logging.SetMinimumLevel(LogLevel.Warning);
        // Built, not published (dotnet run, tests): the page's assets are read where the build left them, in any environment.
        builder.WebHost.UseStaticWebAssets();
        if (url is not null)
        {
            builder.WebHost.UseUrls(url);
        }

        var services = builder.Services;
        services.AddSingleton(AppFolders.Default);
        services.AddSingleton(TimeProvider.System);
        services.AddSingleton<IImageService, ImageService>();
        services.AddSingleton<IMachineConnectionFactory>(new MachineConnectionFactory());
        services.AddSingleton<IRunService, ExecutorRunService>();
        services.AddSingleton<IFileAccess>(sp => new Services.FileAccess(sp.GetRequiredService<AppFolders>()));
        services.AddSingleton<ISettingsStore>(sp => new JsonSettingsStore(sp.GetRequiredService<AppFolders>().SettingsFile));
        services.AddSingleton<IRunLogStore>(sp => new RunLogFolder(sp.GetRequiredService<AppFolders>().RunLogFolder));
        services.AddSingleton<IPresetStore>(sp => new JsonPresetStore(sp.GetRequiredService<AppFolders>().PresetsFile));
        services.AddSingleton(sp => new PresetsViewModel(sp.GetRequiredService<IPresetStore>(), sp.GetRequiredService<MainViewModel>().Job));
        services.AddSingleton(sp =>
        {
            var main = ActivatorUtilities.CreateInstance<MainViewModel>(sp);
            main.Restore();
            return main;
        });
        services.AddRazorComponents().AddInteractiveServerComponents();
        services.AddFluentUIComponents();
        services.AddWindowLifetime();
        configure?.Invoke(services);

        var app = builder.Build();
        app.Use(GuardAsync);
        app.UseAntiforgery();
        app.MapStaticAssets();
        app.MapRazorComponents<Components.App>().AddInteractiveServerRenderMode();
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

        // The page's own connection (Blazor's SignalR hub) needs the circuit the page was served with, not the header.
        if (HttpMethods.IsPost(context.Request.Method) && !context.Request.Headers.ContainsKey(RequestHeader) && !context.Request.Path.StartsWithSegments("/_blazor"))
        {
            context.Response.StatusCode = StatusCodes.Status403Forbidden;
            return context.Response.WriteAsync($"POST needs the {RequestHeader} header");
        }

        return next(context);
    }

    /// <summary>On exit the laser goes off and the ports close, whatever was running.</summary>
    private static void Shutdown(IServiceProvider services)
    {
        var main = services.GetRequiredService<MainViewModel>();
        main.Run.AbortCommand.Execute(null);
        if (main.Machine.Connection is { } connection)
        {
            try
            {
                connection.Gate.OffAsync(CancellationToken.None).WaitAsync(TimeSpan.FromSeconds(2)).GetAwaiter().GetResult();
            }
            catch (Exception ex) when (ex is TimeoutException or Devices.Abstractions.DeviceException or ObjectDisposedException or InvalidOperationException)
            {
                // Nothing more can be done at exit; the gate's watchdog switches the laser off by itself.
            }

            main.Machine.DisconnectCommand.ExecuteAsync(null).WaitAsync(TimeSpan.FromSeconds(3)).ContinueWith(_ => { }, TaskScheduler.Default).GetAwaiter().GetResult();
        }
    }
}
