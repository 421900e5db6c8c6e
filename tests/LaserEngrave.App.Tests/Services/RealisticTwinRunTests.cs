using LaserEngrave.App.Services;
using LaserEngrave.App.ViewModels;
using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Logging;
using LaserEngrave.Devices.Execution;
using LaserEngrave.Simulator;
using LaserEngrave.Simulator.Timing;
using NSubstitute;

namespace LaserEngrave.App.Tests.Services;

/// <summary>The twin the app opens has a realistically late host (issue 22): a run on it still burns nothing on the white.</summary>
public sealed class RealisticTwinRunTests : IAsyncDisposable
{
    private readonly TestFiles.TempFolder _folder = TestFiles.NewFolder();
    private readonly IRunLogStore _store = Substitute.For<IRunLogStore>();
    private readonly MachineViewModel _machine;

    public RealisticTwinRunTests()
    {
        // The app's own twin, unpaced so the test runs in virtual time.
        _machine = new MachineViewModel(new MachineConnectionFactory(MachineConnectionFactory.DefaultSimulatorOptions with { Paced = false }), MachineProfile.Default, new MachineActivity());
    }

    [Fact]
    public void DefaultSimulatorOptions_PacedWithARealisticallyLateHost()
    {
        Assert.True(MachineConnectionFactory.DefaultSimulatorOptions.Paced);
        Assert.Equal(HostLateness.Realistic, MachineConnectionFactory.DefaultSimulatorOptions.HostLateness);
    }

    [Fact(Timeout = 120_000)]
    public async Task Start_OnTheAppsTwin_CompletedWithNothingOnTheWhite()
    {
        var job = new JobViewModel(new ImageService(), MachineProfile.Default, _machine.Activity);
        _store.History().Returns([]);
        var records = new List<RunRecord>();
        _store.Save(Arg.Do<RunRecord>(records.Add)).Returns(new RunLogFiles("/logs/run.json", "/logs/run.txt"));
        var run = new RunViewModel(new EngraveRunService(), job, _machine, new LogViewModel(_store, Substitute.For<IFileAccess>(), job), TimeProvider.System);
        job.LoadImage(TestFiles.WriteChecker(_folder.Path, 8, 4));
        job.EditWidth(0.8);
        job.OriginXMm = 0.5;
        job.OriginYMm = 0.5;
        await _machine.ConnectCommand.ExecuteAsync(null);
        Assert.True(run.StartCommand.CanExecute(null), run.Error ?? _machine.Error);

        await run.StartCommand.ExecuteAsync(null);

        Assert.Equal(RunState.Completed, run.State);
        var simulation = Assert.Single(records).Simulation!;
        Assert.Equal((0L, 0L, 0L), (simulation.LaserOnTravelCount, simulation.MissingPixels, simulation.ExtraPixels));
    }

    public async ValueTask DisposeAsync()
    {
        if (_machine.Connection is { } connection)
        {
            await connection.DisposeAsync();
        }

        _folder.Dispose();
    }
}
