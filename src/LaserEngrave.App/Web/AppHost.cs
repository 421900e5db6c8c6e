using System.Runtime.InteropServices;
using LaserEngrave.App.Components;
using LaserEngrave.App.Services;
using LaserEngrave.App.ViewModels;
using Microsoft.FluentUI.AspNetCore.Components;

namespace LaserEngrave.App.Web;

/// <summary>The composition root: the services, the view-models over them, the page and its API on one local web server.</summary>
public static class AppHost
{
    /// <summary>How long the host gives the server to close its connections on exit (an open page's circuit is dropped, never waited for).</summary>
    public static readonly TimeSpan ShutdownTimeout = TimeSpan.FromMilliseconds(500);

    /// <summary>Builds the app; <paramref name="configure"/> may replace services (tests give fakes or a data folder).</summary>
    /// <param name="url">Where to listen (the app's --urls); null for the configuration's "urls" (ASPNETCORE_URLS, appsettings) or a free port on 127.0.0.1.</param>
    /// <exception cref="ArgumentException">An address is not on this computer; the message is one line naming it.</exception>
    public static WebApplication Build(string[] args, string? url = null, Action<IServiceCollection>? configure = null)
    {
        var builder = WebApplication.CreateBuilder(new WebApplicationOptions { Args = args, ContentRootPath = AppContext.BaseDirectory, ApplicationName = typeof(AppHost).Assembly.GetName().Name });
        builder.Logging.SetMinimumLevel(LogLevel.Warning);
        // A start that fails (a port in use) is told in one line by Program, not as the host's stack trace.
        builder.Logging.AddFilter("Microsoft.Extensions.Hosting.Internal.Host", LogLevel.Critical);
        // Built, not published (dotnet run, tests): the page's assets are read where the build left them, in any environment.
        builder.WebHost.UseStaticWebAssets();
        var urls = url ?? builder.Configuration["urls"] ?? AppOptions.DefaultUrl;
        if (LoopbackAddresses.Problem(builder.Configuration, urls) is { } problem)
        {
            throw new ArgumentException(problem);
        }

        // Set explicitly, so ASPNETCORE_HTTP_PORTS (every interface) never applies.
        builder.WebHost.UseUrls(urls);
        builder.Services.Configure<HostOptions>(o => o.ShutdownTimeout = ShutdownTimeout);

        // One upload limit, the app's: the server's and the form's limits are the same number, so no upload meets another.
        builder.WebHost.ConfigureKestrel(k => k.Limits.MaxRequestBodySize = IFileAccess.MaxUploadBytes + 1);
        builder.Services.Configure<Microsoft.AspNetCore.Http.Features.FormOptions>(o => o.MultipartBodyLengthLimit = IFileAccess.MaxUploadBytes);

        var services = builder.Services;
        ApiRequests.Configure(services);
        services.AddSingleton<AccessToken>();
        services.AddSingleton<LaunchCodes>();
        services.AddSingleton(AppFolders.Default);
        services.AddSingleton(TimeProvider.System);
        services.AddSingleton<MachineActivity>();
        services.AddSingleton<IImageService, ImageService>();
        services.AddSingleton<IMachineConnectionFactory>(new MachineConnectionFactory());
        services.AddSingleton<IRunService, EngraveRunService>();
        services.AddSingleton<IFileAccess>(sp => new Services.FileAccess(sp.GetRequiredService<AppFolders>()));
        services.AddSingleton<IJobFiles>(sp => new JobFiles(sp.GetRequiredService<AppFolders>(), () => sp.GetRequiredService<MainViewModel>().Job.Profile, sp.GetRequiredService<TimeProvider>()));
        services.AddSingleton<ISettingsStore>(sp => new JsonSettingsStore(sp.GetRequiredService<AppFolders>().SettingsFile));
        services.AddSingleton<IRunLogStore>(sp => new RunLogFolder(sp.GetRequiredService<AppFolders>().RunLogFolder, sp.GetRequiredService<AppFolders>().DataFolder));
        services.AddSingleton<IPresetStore>(sp => new JsonPresetStore(sp.GetRequiredService<AppFolders>().PresetsFile));
        services.AddSingleton(sp => new PresetsViewModel(sp.GetRequiredService<IPresetStore>(), sp.GetRequiredService<MainViewModel>().Job));
        services.AddSingleton(sp => new CalibrationViewModel(sp.GetRequiredService<MainViewModel>(), sp.GetRequiredService<AppFolders>().DataFolder));
        services.AddSingleton(sp => new AlignmentViewModel(sp.GetRequiredService<MainViewModel>(), sp.GetRequiredService<AppFolders>().DataFolder));
        services.AddSingleton<ICameraService>(sp => new CameraService(sp.GetRequiredService<MainViewModel>()));
        services.AddSingleton(sp => new CameraViewModel(sp.GetRequiredService<ICameraService>(), (mark, xMm, yMm) =>
        {
            // A mark picked in the camera's image is the Alignment panel's stage position of that mark.
            var alignment = sp.GetRequiredService<AlignmentViewModel>();
            if (mark == 1)
            {
                (alignment.Stage1XMm, alignment.Stage1YMm) = (xMm, yMm);
            }
            else
            {
                (alignment.Stage2XMm, alignment.Stage2YMm) = (xMm, yMm);
            }
        }));
        services.AddSingleton<IMachineCheckService, MachineCheckService>();
        services.AddSingleton(sp => new CommissionViewModel(sp.GetRequiredService<MainViewModel>(), sp.GetRequiredService<IMachineCheckService>(), sp.GetRequiredService<AppFolders>().DataFolder, sp.GetRequiredService<TimeProvider>()));
        services.AddSingleton<IMarkService>(sp => new MarkService(sp.GetRequiredService<AppFolders>(), () => sp.GetRequiredService<MainViewModel>().Job.Profile, sp.GetRequiredService<TimeProvider>()));
        services.AddSingleton(sp => new MarkViewModel(sp.GetRequiredService<IMarkService>(), path => sp.GetRequiredService<MainViewModel>().Layers.Open(path), () => sp.GetRequiredService<MainViewModel>().Log.SampleId));
        services.AddSingleton(sp =>
        {
            var main = ActivatorUtilities.CreateInstance<MainViewModel>(sp);
            // The last image opens in the background: a big one never holds up the first page (its progress shows there).
            _ = main.Restore().ContinueWith(t => _ = t.Exception, TaskScheduler.Default);
            return main;
        });
        services.AddOpenApi(ApiDescription.Configure);
        services.AddRazorComponents().AddInteractiveServerComponents();
        services.AddFluentUIComponents();
        services.AddWindowLifetime();
        // No antiforgery cookie: a cookie cannot be kept to one port, so every server on 127.0.0.1 would receive it, and
        // it authorises nothing here (the page posts no forms; every request shows the token in a header instead).
        services.AddScoped<Microsoft.AspNetCore.Components.Forms.AntiforgeryStateProvider, NoAntiforgeryState>();
        configure?.Invoke(services);

        var app = builder.Build();
        app.Use(GuardAsync);
        app.Use(ApiRequests.ReadAsync);
        app.UseAntiforgery();
        app.MapStaticAssets();
        app.MapRazorComponents<Components.App>().AddInteractiveServerRenderMode(o => o.ContentSecurityFrameAncestorsPolicy = "'none'");
        SessionEndpoints.Map(app);
        ApiEndpoints.Map(app);
        app.MapOpenApi(ApiDescription.Path);
        app.Lifetime.ApplicationStopping.Register(() => Shutdown(app.Services));
        app.Lifetime.ApplicationStopping.Register(() => app.Services.GetRequiredService<LaunchCodes>().RemoveFiles());

        // The run log's JSON writer is built in the background, so the first log (an abort's at exit too) does not wait for it.
        app.Lifetime.ApplicationStarted.Register(() => _ = Task.Run(Core.Logging.RunRecordJson.Prepare));
        return app;
    }

    /// <summary>
    /// Refuses other hosts (DNS rebinding), requests from another page (Origin) and every request for the API or the
    /// page's hub without the start's token in a header (or, for the hub's WebSocket, Blazor's access_token). Nothing the
    /// browser sends by itself (cookies) is a credential: the page keeps the token in its own tab and shows it, so no
    /// other server on 127.0.0.1 ever receives it.
    /// </summary>
    private static Task GuardAsync(HttpContext context, RequestDelegate next)
    {
        var request = context.Request;
        var response = context.Response;
        var host = request.Host.Host;
        if (host is not ("127.0.0.1" or "localhost" or "[::1]" or "::1"))
        {
            response.StatusCode = StatusCodes.Status403Forbidden;
            return Task.CompletedTask;
        }

        // A page of another origin (another port on 127.0.0.1 is one: the same "site" to a browser) is refused whatever
        // it carries; scripts send no Origin and show the token instead.
        if (request.Headers.Origin is { Count: > 0 } origin && !IsOwnOrigin(request, origin.ToString()))
        {
            response.StatusCode = StatusCodes.Status403Forbidden;
            return response.WriteAsync($"requests from another page ({origin}) are refused: only the app's own page or a script may call it");
        }

        // The page never lets another page frame it (Blazor's own policy says the same: frame-ancestors 'none'), and
        // sends no address onwards.
        response.Headers.XFrameOptions = "DENY";
        response.Headers["Referrer-Policy"] = "no-referrer";

        // The token is never taken from a page's address (it would stay in the browser's history): an old bookmark or
        // a pasted start line of an earlier version is refused whatever it carries.
        if (request.Query.ContainsKey(AccessToken.QueryName))
        {
            return Unauthorized(response, "a token in the address is not taken: open the app from the window it opened or the launch address it printed (each works once)");
        }

        var token = context.RequestServices.GetRequiredService<AccessToken>();
        if (IsPublic(request) || token.IsShownBy(request, hub: request.Path.StartsWithSegments(BlazorHubPath)))
        {
            return next(context);
        }

        return Unauthorized(response, $"this needs the start's token: open the app from its window or its launch address, or send 'Authorization: Bearer TOKEN' or '{AccessToken.HeaderName}: TOKEN' (TOKEN from connection.json)");
    }

    /// <summary>Gives the page no antiforgery token, so none is made and no cookie is set for it.</summary>
    private sealed class NoAntiforgeryState : Microsoft.AspNetCore.Components.Forms.AntiforgeryStateProvider
    {
        public override Microsoft.AspNetCore.Components.Forms.AntiforgeryRequestToken? GetAntiforgeryToken() => null;
    }

    /// <summary>Blazor's SignalR hub, the page's own connection.</summary>
    internal const string BlazorHubPath = "/_blazor";

    /// <summary>Where the app's state and commands are: the API, its description and the page's hub.</summary>
    private static readonly string[] GuardedPaths = ["/api", "/openapi", BlazorHubPath];

    /// <summary>
    /// The page's shell and its static files (no state: the page is not prerendered), the launch code's trade and the
    /// token's proof (SessionEndpoints), Blazor's list of script
    /// initializers, and the beacon with which a closing page ends its own circuit (it names the circuit's secret id
    /// and cannot carry a header). Everything else needs the token.
    /// </summary>
    private static bool IsPublic(HttpRequest request)
    {
        if (SessionEndpoints.IsSessionRoute(request))
        {
            return true;
        }

        var path = request.Path;
        if (HttpMethods.IsGet(request.Method) || HttpMethods.IsHead(request.Method))
        {
            return path.Equals(BlazorHubPath + "/initializers", StringComparison.OrdinalIgnoreCase)
                || !GuardedPaths.Any(p => path.StartsWithSegments(p, StringComparison.OrdinalIgnoreCase));
        }

        return HttpMethods.IsPost(request.Method) && path.Equals(BlazorHubPath + "/disconnect", StringComparison.OrdinalIgnoreCase);
    }

    /// <summary>Whether <paramref name="origin"/> is the app's own scheme, host and port, as the request reached it.</summary>
    internal static bool IsOwnOrigin(HttpRequest request, string origin) =>
        string.Equals(origin, $"{request.Scheme}://{request.Host.Value}", StringComparison.OrdinalIgnoreCase);

    private static Task Unauthorized(HttpResponse response, string message)
    {
        response.StatusCode = StatusCodes.Status401Unauthorized;
        response.Headers.WWWAuthenticate = "Bearer";
        return response.WriteAsync(message);
    }

    /// <summary>How long the exit waits for an aborted run to write its log before the ports are closed regardless.</summary>
    /// <remarks>
    /// The wait ends as soon as the run has ended, so only a stuck run makes it last. An abort takes milliseconds, but on a
    /// loaded computer the laser-off sequence and the log (the first JSON the process writes, if no earlier run wrote one)
    /// took over a second, and with a one-second bound the app exited without the log (a SIGTERM test beside busy loops).
    /// </remarks>
    internal static readonly TimeSpan RunEndWait = TimeSpan.FromSeconds(10);

    /// <summary>Stops the app on a hang-up as on Ctrl+C; null where the platform has no such signal.</summary>
    /// <remarks>Windows ends the process once its console-close handler returns: the handler holds it until the app has stopped.</remarks>
    internal static PosixSignalRegistration? StopOnHangUp(IHostApplicationLifetime lifetime)
    {
        if (OperatingSystem.IsAndroid() || OperatingSystem.IsIOS() || OperatingSystem.IsTvOS() || OperatingSystem.IsBrowser())
        {
            return null;
        }

        try
        {
            return PosixSignalRegistration.Create(PosixSignal.SIGHUP, context =>
            {
                context.Cancel = true;
                lifetime.StopApplication();
                if (OperatingSystem.IsWindows())
                {
                    _ = lifetime.ApplicationStopped.WaitHandle.WaitOne(RunEndWait);
                }
            });
        }
        catch (PlatformNotSupportedException)
        {
            return null;
        }
    }

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
            // The runs' own off path (every path when OFF is in doubt, the port closed last); it settles every failure itself.
            // Nothing more can be done at exit past the bound: the gate's watchdog switches the laser off by itself.
            var off = new Devices.Execution.LaserOff(connection.Gate, connection.TimeProvider)
                .SwitchOffAsync(Devices.Execution.LaserOff.ConfirmWindow(Core.Planning.ProcessSettings.FromProfile(connection.Profile), connection.Profile), connection.Profile.Gate.WatchdogMs);
            _ = off.Wait(TimeSpan.FromMilliseconds(1000));

            _ = main.Machine.CloseAsync().Wait(TimeSpan.FromMilliseconds(300));
        }
    }
}
