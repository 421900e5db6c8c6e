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
    {
        var settings = Substitute.For<ISettingsStore>();
        settings.Load().Returns(new AppSettings());
        var store = Substitute.For<IRunLogStore>();
        store.History().Returns([]);
        _main = new MainViewModel(
            new ImageService(), new MachineConnectionFactory(new SimulatorOptions { FirmwareVersion = 506 }), Substitute.For<IRunService>(), store, settings,
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
        var profile = MachineProfile.Load(Path.Combine(_folder.Path, "machine-profile.json"));
        Assert.NotEqual(MachineProfile.Default.Latency, profile.Latency);
        Assert.Equal(profile.Latency, _main.Machine.Profile.Latency);
        var report = await File.ReadAllTextAsync(_commission.ReportPath!, TestContext.Current.CancellationToken);
        Assert.Contains("ok     X move: device 1 (X) sent to 10079 microsteps", report, StringComparison.Ordinal);
        Assert.False(_main.Activity.IsBusy);
        Assert.True(_main.Machine.XHomed);
    }

    public async ValueTask DisposeAsync()
    {
        if (_main.Machine.Connection is { } connection)
        {
            await connection.DisposeAsync();
        }

        _folder.Dispose();
    }
}
