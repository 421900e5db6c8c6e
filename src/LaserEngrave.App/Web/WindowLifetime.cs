using LaserEngrave.App.ViewModels;
using Microsoft.AspNetCore.Components.Server.Circuits;

namespace LaserEngrave.App.Web;

/// <summary>How long the app outlives its last window; null keeps it running (a server started with --no-browser).</summary>
public sealed record WindowLifetimeOptions(TimeSpan? Grace);

/// <summary>
/// Ends the app once its window has been closed for <see cref="WindowLifetimeOptions.Grace"/> and no run is under way;
/// a run keeps it alive (a window opened again shows the run), and it ends after the run once no window is left.
/// </summary>
/// <remarks>Counts live connections, not circuits: a closed window drops its connection at once, its circuit only minutes later.</remarks>
public sealed class WindowLifetime : IDisposable
{
    private readonly TimeProvider _time;
    private readonly Func<bool> _runActive;
    private readonly Action _stop;
    private readonly TimeSpan? _grace;
    private readonly Lock _lock = new();
    private int _windows;
    private bool _seen;
    private ITimer? _timer;

    public WindowLifetime(WindowLifetimeOptions options, TimeProvider time, Func<bool> runActive, Action stop)
    {
        ArgumentNullException.ThrowIfNull(options);
        ArgumentNullException.ThrowIfNull(time);
        ArgumentNullException.ThrowIfNull(runActive);
        ArgumentNullException.ThrowIfNull(stop);
        _grace = options.Grace;
        _time = time;
        _runActive = runActive;
        _stop = stop;
    }

    public int OpenWindows
    {
        get
        {
            lock (_lock)
            {
                return _windows;
            }
        }
    }

    /// <summary>Whether the app is counting down to its end.</summary>
    public bool Ending
    {
        get
        {
            lock (_lock)
            {
                return _timer is not null;
            }
        }
    }

    public void WindowOpened()
    {
        lock (_lock)
        {
            _windows++;
            _seen = true;
        }

        Check();
    }

    public void WindowClosed()
    {
        lock (_lock)
        {
            _windows = Math.Max(0, _windows - 1);
        }

        Check();
    }

    /// <summary>Called when a run starts or ends: the end of a run may be what lets the app end.</summary>
    public void Check()
    {
        lock (_lock)
        {
            // Before the first window connects the app must not end: the browser may still be starting.
            var idle = _grace is not null && _seen && _windows == 0 && !_runActive();
            if (idle && _timer is null)
            {
                _timer = _time.CreateTimer(_ => Expire(), null, _grace!.Value, Timeout.InfiniteTimeSpan);
            }
            else if (!idle && _timer is not null)
            {
                _timer.Dispose();
                _timer = null;
            }
        }
    }

    private void Expire()
    {
        lock (_lock)
        {
            if (_timer is null || _windows > 0 || _runActive())
            {
                return;
            }
        }

        _stop();
    }

    public void Dispose()
    {
        lock (_lock)
        {
            _timer?.Dispose();
            _timer = null;
        }
    }

    /// <summary>Tells the lifetime when a window's connection comes and goes.</summary>
    internal sealed class Handler(WindowLifetime lifetime) : CircuitHandler
    {
        public override Task OnConnectionUpAsync(Circuit circuit, CancellationToken cancellationToken)
        {
            lifetime.WindowOpened();
            return Task.CompletedTask;
        }

        public override Task OnConnectionDownAsync(Circuit circuit, CancellationToken cancellationToken)
        {
            lifetime.WindowClosed();
            return Task.CompletedTask;
        }
    }
}

/// <summary>Registers <see cref="WindowLifetime"/> over the app's run and host.</summary>
internal static class WindowLifetimeRegistration
{
    public static IServiceCollection AddWindowLifetime(this IServiceCollection services)
    {
        services.AddSingleton(new WindowLifetimeOptions(null));
        services.AddSingleton(sp =>
        {
            var main = sp.GetRequiredService<MainViewModel>();
            var run = main.Run;
            var host = sp.GetRequiredService<IHostApplicationLifetime>();
            // Whatever holds the machine (a run, homing, a test move) keeps the app alive, not only a run.
            var lifetime = new WindowLifetime(sp.GetRequiredService<WindowLifetimeOptions>(), sp.GetRequiredService<TimeProvider>(), () => run.IsActive || main.Activity.IsBusy, host.StopApplication);
            run.PropertyChanged += (_, e) =>
            {
                if (e.PropertyName == nameof(RunViewModel.State))
                {
                    lifetime.Check();
                }
            };
            main.Activity.PropertyChanged += (_, e) =>
            {
                if (e.PropertyName == nameof(Services.MachineActivity.Current))
                {
                    lifetime.Check();
                }
            };
            return lifetime;
        });
        services.AddScoped<CircuitHandler, WindowLifetime.Handler>();
        return services;
    }
}
