using System.Diagnostics;

namespace LaserEngrave.Cli.Tests;

/// <summary>`laserengrave simulator` in a child process, stopped on dispose.</summary>
internal sealed class SimulatorProcess : IAsyncDisposable
{
    private readonly Process _process;

    private SimulatorProcess(Process process) => _process = process;

    /// <summary>Starts the simulator on the A ends of the two pairs; the B ends are the host's.</summary>
    public static async Task<SimulatorProcess> StartAsync(LaserEngrave.Testing.SocatPtyPair stage, LaserEngrave.Testing.SocatPtyPair laser, CancellationToken cancellationToken)
    {
        var cli = typeof(Program).Assembly.Location;
        var dotnet = Environment.GetEnvironmentVariable("DOTNET_HOST_PATH") is { Length: > 0 } host ? host : "dotnet";
        // On ports the simulator runs on the wall clock: it starts 1 mm from home so that a run's homing takes a moment, not 15 s.
        var options = Path.Combine(Path.GetTempPath(), $"le-sim-options-{Guid.NewGuid():N}.json");
        await File.WriteAllTextAsync(options, """{ "startMm": 1 }""", cancellationToken);
        var start = new ProcessStartInfo(dotnet)
        {
            ArgumentList = { cli, "simulator", "--stage-port", stage.A, "--laser-port", laser.A, "--sim-options", options },
            RedirectStandardOutput = true,
            RedirectStandardError = true,
            UseShellExecute = false,
        };
        var process = Process.Start(start) ?? throw new InvalidOperationException("laserengrave simulator did not start");
        var ready = new TaskCompletionSource(TaskCreationOptions.RunContinuationsAsynchronously);
        process.OutputDataReceived += (_, e) =>
        {
            if (e.Data?.Contains("Ctrl+C", StringComparison.Ordinal) == true)
            {
                ready.TrySetResult();
            }
        };
        process.ErrorDataReceived += (_, _) => { };
        process.BeginOutputReadLine();
        process.BeginErrorReadLine();
        var simulator = new SimulatorProcess(process);
        try
        {
            await ready.Task.WaitAsync(TimeSpan.FromSeconds(30), cancellationToken);
            await WarmUpAsync(stage.B, laser.B, cancellationToken);
        }
        catch
        {
            await simulator.DisposeAsync();
            throw;
        }
        finally
        {
            // Read at start-up: once the simulator is ready (or gone) the file has done its work.
            File.Delete(options);
        }

        return simulator;
    }

    // A fresh simulator process compiles its code paths on the first frames; on a loaded 2-core machine that can take
    // longer than a device's 500 ms reply timeout, which real devices never do. One identify round warms it up.
    private static async Task WarmUpAsync(string stage, string laser, CancellationToken cancellationToken)
    {
        for (var attempt = 0; attempt < 5; attempt++)
        {
            var (stageExit, _, _) = await CliHarness.RunAsync("stage", "--port", stage, "identify");
            var (laserExit, _, _) = await CliHarness.RunAsync("laser", "--port", laser, "status");
            if (stageExit == 0 && laserExit == 0)
            {
                return;
            }

            await Task.Delay(200, cancellationToken);
        }
    }

    public async ValueTask DisposeAsync()
    {
        if (!_process.HasExited)
        {
            _process.Kill(entireProcessTree: true);
            await _process.WaitForExitAsync().WaitAsync(TimeSpan.FromSeconds(10));
        }

        _process.Dispose();
    }
}
