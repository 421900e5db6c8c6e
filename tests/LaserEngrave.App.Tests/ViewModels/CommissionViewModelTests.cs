using LaserEngrave.App.Services;
using LaserEngrave.App.ViewModels;
using LaserEngrave.Core.Geometry;
using LaserEngrave.Devices.Machine;
using LaserEngrave.Simulator;
using NSubstitute;

namespace LaserEngrave.App.Tests.ViewModels;

/// <summary>The Commission panel's check on the in-process simulator (virtual time): the command line's machine check, step by step.</summary>
public sealed class CommissionViewModelTests : IAsyncDisposable
{
    private readonly TestFiles.TempFolder _folder = TestFiles.NewFolder();
    private readonly MainViewModel _main;
    private readonly CommissionViewModel _commission;

    public CommissionViewModelTests()
        : this(asIfReal: false)
    {
    }

    /// <param name="asIfReal">The simulator as the app would see a real machine (<see cref="IMachineConnection.IsSimulated"/> false).</param>
    private CommissionViewModelTests(bool asIfReal)
    {
        var settings = Substitute.For<ISettingsStore>();
        settings.Load().Returns(new AppSettings());
        var store = Substitute.For<IRunLogStore>();
        store.History().Returns([]);
        IMachineConnectionFactory factory = new MachineConnectionFactory(new SimulatorOptions { FirmwareVersion = 506 });
        _main = new MainViewModel(
            new ImageService(), asIfReal ? new AsIfReal(factory) : factory, Substitute.For<IRunService>(), store, settings,
            Substitute.For<IFileAccess>(), TimeProvider.System, new MachineActivity(), new JobFiles(new AppFolders(_folder.Path)));
        _commission = new CommissionViewModel(_main, new MachineCheckService(), _folder.Path, TimeProvider.System) { DistanceMm = 1, Exchanges = 10 };
    }

    [Fact(Timeout = 120_000)]
    public async Task Check_OnTheSimulatorBeamBlocked_EveryStepPassesInOrderAndTheFindingsAreWritten()
    {
        var seen = new List<string>();
        _commission.PropertyChanged += (_, e) =>
        {
            if (e.PropertyName == nameof(CommissionViewModel.Steps))
            {
                lock (seen)
                {
                    seen.Add(_commission.Steps[^1].Name);
                }
            }
        };
        await _main.Machine.ConnectCommand.ExecuteAsync(null);
        Assert.Null(_main.Machine.Error);
        _commission.BeamBlocked = true;

        await _commission.CheckCommand.ExecuteAsync(null);

        Assert.Null(_commission.Error);
        Assert.True(_commission.Passed, string.Join("\n", _commission.Steps.Select(s => $"{s.Result} {s.Name}: {s.Finding}")));
        Assert.Equal(MachineCheck.StepNames, _commission.Steps.Select(s => s.Name));
        Assert.Equal(MachineCheck.StepNames, seen.Distinct());
        Assert.Contains("firmware 5.06 (homes at the Target Speed", _commission.Steps.Single(s => s.Name == "X axis").Finding, StringComparison.Ordinal);
        Assert.Contains("watchdog tripped", _commission.Steps.Single(s => s.Name == "gate watchdog").Finding, StringComparison.Ordinal);
        Assert.Equal("Result: every step passed", _commission.Result);
        // Issue 31, finding 9: the simulator's latencies once went into the app's one machine profile (the box ticked by default).
        Assert.False(File.Exists(Path.Combine(_folder.Path, "machine-profile.json")));
        var profile = MachineProfile.Load(Path.Combine(_folder.Path, CommissionViewModel.SimulatorProfileName));
        Assert.NotEqual(MachineProfile.Default.Latency, profile.Latency);
        Assert.Equal(MachineProfile.Default.Latency, _main.Machine.Profile.Latency);
        Assert.StartsWith("Written: the simulator's latencies into ", _commission.ProfileNote, StringComparison.Ordinal);
        Assert.EndsWith("the machine profile was left as it was", _commission.ProfileNote, StringComparison.Ordinal);
        var report = await File.ReadAllTextAsync(_commission.ReportPath!, TestContext.Current.CancellationToken);
        Assert.Contains("ok     X move: device 1 (X) sent to 10079 microsteps", report, StringComparison.Ordinal);
        Assert.False(_main.Activity.IsBusy);
        Assert.True(_main.Machine.XHomed);
    }

    [Fact(Timeout = 120_000)]
    public async Task Check_OnARealMachine_TheLatenciesGoIntoTheMachineProfileInUse()
    {
        await using var real = new CommissionViewModelTests(asIfReal: true);
        await real._main.Machine.ConnectCommand.ExecuteAsync(null);
        Assert.Null(real._main.Machine.Error);

        await real._commission.CheckCommand.ExecuteAsync(null);

        var profile = MachineProfile.Load(Path.Combine(real._folder.Path, "machine-profile.json"));
        Assert.NotEqual(MachineProfile.Default.Latency, profile.Latency);
        Assert.Equal(profile.Latency, real._main.Machine.Profile.Latency);
        Assert.False(File.Exists(Path.Combine(real._folder.Path, CommissionViewModel.SimulatorProfileName)));
    }

    public async ValueTask DisposeAsync()
    {
        if (_main.Machine.Connection is { } connection)
        {
            await connection.DisposeAsync();
        }

        _folder.Dispose();
    }

    /// <summary>Opens the simulator and presents it as a real machine, as serial ports would be.</summary>
    private sealed class AsIfReal(IMachineConnectionFactory inner) : IMachineConnectionFactory
    {
        public async Task<IMachineConnection> ConnectAsync(MachineChoice choice, MachineProfile profile, CancellationToken cancellationToken) =>
            new Real(await inner.ConnectAsync(choice, profile, cancellationToken));

        public IReadOnlyList<string> ListPorts() => [];

        private sealed class Real(IMachineConnection simulator) : IMachineConnection
        {
            public string Description => "stage COM3, laser COM4";

            public MachineProfile Profile => simulator.Profile;

            public TimeProvider TimeProvider => simulator.TimeProvider;

            public bool IsSimulated => false;

            public Devices.Abstractions.IStage Stage => simulator.Stage;

            public Devices.Abstractions.ILaserGate Gate => simulator.Gate;

            public Devices.Machine.ILatencyProbe Latency => simulator.Latency;

            public Core.Logging.IRunInspector? Inspector => null;

            public ValueTask DisposeAsync() => simulator.DisposeAsync();
        }
    }
}
