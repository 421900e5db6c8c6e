using System.Globalization;
using CommunityToolkit.Mvvm.ComponentModel;
using CommunityToolkit.Mvvm.Input;
using LaserEngrave.App.Services;
using LaserEngrave.Core.Geometry;
using LaserEngrave.Devices.Abstractions;
using LaserEngrave.Devices.Machine;

namespace LaserEngrave.App.ViewModels;

/// <summary>
/// The Commission view, the command line's <c>machine check</c> (docs/commissioning.md): on the connected machine, identify
/// both axes and the gate, home, move each axis a known distance and read it back, measure the latencies, trip the gate's
/// watchdog once when the person at the machine has said the beam is blocked; then the latencies into the profile and a
/// printable report, as the command line writes them.
/// </summary>
/// <remarks>
/// The beam is confirmed before the check starts, not at its watchdog step: the check runs on the machine's clock (the
/// simulation's loop in virtual time), which cannot wait for a person. The check holds the machine as a test move does,
/// so Stop (and Esc) ends it, the laser switched off.
/// </remarks>
public sealed partial class CommissionViewModel : ObservableObject
{
    /// <summary>Most round trips per device (as the command line's <c>--count</c> allows).</summary>
    public const int MaxExchanges = 100_000;

    private static readonly MachineOperation Checking = MachineOperation.TestMove("machine check", "Checking the machine: identity, homing, moves, latencies, the gate's watchdog…");

    private readonly MainViewModel _main;
    private readonly IMachineCheckService _checks;
    private readonly string _dataFolder;
    private readonly string _reportFolder;
    private readonly TimeProvider _time;
    private readonly Lock _stepsLock = new();

    /// <param name="main">The window: its machine, and the profile the latencies are written into.</param>
    /// <param name="checks">Runs the check.</param>
    /// <param name="dataFolder">The app's data folder: reports go into its reports/ folder, a new profile beside the settings.</param>
    /// <param name="time">The wall clock, for the report's date.</param>
    public CommissionViewModel(MainViewModel main, IMachineCheckService checks, string dataFolder, TimeProvider time)
    {
        ArgumentNullException.ThrowIfNull(main);
        ArgumentNullException.ThrowIfNull(checks);
        ArgumentException.ThrowIfNullOrWhiteSpace(dataFolder);
        ArgumentNullException.ThrowIfNull(time);
        _main = main;
        _checks = checks;
        _reportFolder = Path.Combine(dataFolder, "reports");
        _dataFolder = dataFolder;
        _time = time;
        main.Machine.PropertyChanged += (_, _) => Refresh();
        main.Activity.PropertyChanged += (_, _) => Refresh();
    }

    /// <summary>How far each axis is moved from home and read back, mm.</summary>
    [ObservableProperty]
    public partial double DistanceMm { get; set; } = 10;

    /// <summary>Round trips per device for the latencies.</summary>
    [ObservableProperty]
    public partial double Exchanges { get; set; } = 100;

    /// <summary>The person at the machine says the beam is blocked: the watchdog step fires the laser; otherwise it is skipped.</summary>
    [ObservableProperty]
    public partial bool BeamBlocked { get; set; }

    /// <summary>Write the measured latencies into the machine profile.</summary>
    [ObservableProperty]
    public partial bool WriteProfile { get; set; } = true;

    /// <summary>The steps ended so far, in order.</summary>
    [ObservableProperty]
    public partial IReadOnlyList<MachineCheckStep> Steps { get; private set; } = [];

    [ObservableProperty]
    [NotifyCanExecuteChangedFor(nameof(CheckCommand), nameof(StopCommand))]
    public partial bool IsChecking { get; private set; }

    /// <summary>The report's last line once the check ended: every step passed, or not.</summary>
    [ObservableProperty]
    public partial string? Result { get; private set; }

    /// <summary>Whether every step of the last check passed.</summary>
    [ObservableProperty]
    public partial bool? Passed { get; private set; }

    /// <summary>Where the last report was written.</summary>
    [ObservableProperty]
    public partial string? ReportPath { get; private set; }

    /// <summary>What became of the latencies: written into which profile, or why not.</summary>
    [ObservableProperty]
    public partial string? ProfileNote { get; private set; }

    /// <summary>Why the check did not start or was stopped, one line.</summary>
    [ObservableProperty]
    public partial string? Error { get; private set; }

    /// <summary>The step under way while checking (the first not ended yet).</summary>
    public string? CurrentStep => IsChecking ? MachineCheck.StepNames.Skip(Steps.Count).FirstOrDefault() : null;

    /// <summary>Connected, nothing holds the machine, not checking.</summary>
    public bool CanCheck => !IsChecking && _main.Machine.CanUseMachine;

    /// <summary>Checks the connected machine, step by step; the laser is off at the end whatever happened.</summary>
    [RelayCommand(CanExecute = nameof(CanCheck))]
    private async Task CheckAsync()
    {
        var machine = _main.Machine;
        var profile = machine.Profile;
        if (Problem(profile) is { } problem)
        {
            Error = problem;
            return;
        }

        if (machine.Connection is not { } connection)
        {
            Error = "not connected: connect to the simulator or the machine first";
            return;
        }

        if (!machine.Activity.TryBegin(Checking, out var lease, out var refusal))
        {
            Error = refusal;
            return;
        }

        Error = Result = ReportPath = ProfileNote = null;
        Passed = null;
        Steps = [];
        IsChecking = true;
        var at = _time.GetUtcNow();
        MachineCheckReport? report = null;
        try
        {
            using (lease)
            {
                report = await _checks.RunAsync(connection, profile, DistanceMm, (int)Exchanges, BeamBlocked, new StepProgress(this), lease.CancellationToken);
            }
        }
        catch (OperationCanceledException)
        {
            Error = "stopped: the check did not finish (the laser was switched off); nothing was written";
        }
        catch (Exception ex) when (ex is DeviceException or IOException or TimeoutException or InvalidOperationException or ObjectDisposedException)
        {
            Error = $"the check stopped: {ex.Message}; nothing was written";
        }
        finally
        {
            IsChecking = false;
        }

        if (report is not null)
        {
            Steps = report.Steps;
            Finish(report, connection.Description, profile, at, connection.IsSimulated);
        }

        // The check homed and moved the axes: the Machine panel reads them again.
        try
        {
            await machine.RefreshStateAsync(CancellationToken.None);
        }
        catch (Exception ex) when (ex is DeviceException or IOException or TimeoutException or InvalidOperationException or ObjectDisposedException)
        {
            machine.Error = ex.Message;
        }
    }

    private bool CanStop() => IsChecking;

    /// <summary>Stops the check under way (the laser is switched off); nothing is written.</summary>
    [RelayCommand(CanExecute = nameof(CanStop))]
    private void Stop()
    {
        if (_main.Activity.Current == Checking)
        {
            _main.Activity.CancelCurrent();
        }
    }

    /// <summary>Why the check cannot run with these settings on <paramref name="profile"/>'s machine, one line; null when it can.</summary>
    public string? Problem(MachineProfile profile)
    {
        ArgumentNullException.ThrowIfNull(profile);
        var c = CultureInfo.InvariantCulture;
        var travel = Math.Min(profile.X.TravelMm, profile.Y.TravelMm);
        if (!double.IsFinite(DistanceMm) || DistanceMm <= 0 || DistanceMm > travel)
        {
            return string.Create(c, $"the distance {DistanceMm} mm must be above 0 and at most the travel ({travel} mm)");
        }

        return Exchanges is < 1 or > MaxExchanges || Exchanges != Math.Floor(Exchanges) ? string.Create(c, $"the round trips {Exchanges} must be a whole number from 1 to {MaxExchanges}") : null;
    }

    // The profile and the report, as `machine check --profile FILE --write --report FILE` writes them.
    /// <summary>Where a check on the simulator stores its latencies: a profile of its own in the data folder, never the machine's.</summary>
    public const string SimulatorProfileName = "simulator-profile.json";

    // A check on the simulator measures the simulator: its latencies go into a profile of the simulator's own, and the app
    // keeps the machine profile it uses (a practice check once overwrote the real machine's figures).
    private void Finish(MachineCheckReport report, string machine, MachineProfile profile, DateTimeOffset at, bool simulated)
    {
        Passed = report.Passed;
        var lines = report.Lines(machine, at).ToList();
        Result = lines[^1];
        string written;
        if (!WriteProfile)
        {
            written = "Not written: tick \"Write the latencies into the profile\" to store them";
        }
        else if (report.Latency is not { } latency)
        {
            written = "Not written: the latencies were not measured";
        }
        else
        {
            var path = simulated ? Path.Combine(_dataFolder, SimulatorProfileName) : _main.Settings.ProfilePath ?? Path.Combine(_dataFolder, "machine-profile.json");
            try
            {
                var updated = profile with { Latency = latency };
                if (simulated)
                {
                    // The simulator's own profile: written under the same run interlock, never put in use as the machine's.
                    _main.WriteProfile(path, updated);
                    written = $"Written: the simulator's latencies into {path}, the simulator's own profile; the machine profile was left as it was";
                }
                else
                {
                    _main.SaveProfile(path, updated);
                    written = $"Written: the latency section of {path}";
                }
            }
            catch (Exception ex) when (ex is IOException or UnauthorizedAccessException or ProfileException or MachineBusyException)
            {
                written = $"Not written: {ex.Message}";
            }
        }

        ProfileNote = written;
        lines.Add(written);
        try
        {
            Directory.CreateDirectory(_reportFolder);
            var path = Path.Combine(_reportFolder, $"machine-check_{at.ToString("yyyy-MM-dd_HHmmss", CultureInfo.InvariantCulture)}.txt");
            File.WriteAllLines(path, lines);
            ReportPath = path;
        }
        catch (Exception ex) when (ex is IOException or UnauthorizedAccessException)
        {
            Error = $"the report could not be written in {_reportFolder}: {ex.Message}";
        }
    }

    private void Refresh()
    {
        CheckCommand.NotifyCanExecuteChanged();
        StopCommand.NotifyCanExecuteChanged();
    }

    partial void OnStepsChanged(IReadOnlyList<MachineCheckStep> value) => OnPropertyChanged(nameof(CurrentStep));

    partial void OnIsCheckingChanged(bool value) => OnPropertyChanged(nameof(CurrentStep));

    // Each step as it ends, from the machine's thread: the list is replaced whole, so the view reads a consistent one.
    private sealed class StepProgress(CommissionViewModel owner) : IProgress<MachineCheckStep>
    {
        public void Report(MachineCheckStep value)
        {
            lock (owner._stepsLock)
            {
                owner.Steps = [.. owner.Steps, value];
            }
        }
    }
}
