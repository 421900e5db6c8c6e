using LaserEngrave.App.Services;
using LaserEngrave.App.ViewModels;
using LaserEngrave.Core.Geometry;
using LaserEngrave.Simulator;
using NSubstitute;

namespace LaserEngrave.App.Tests.ViewModels;

/// <summary>The run bar's choice of what Start starts, once written in its markup (issue 35: no decision in .razor files).</summary>
public sealed class RunBarViewModelTests : IDisposable
{
    private readonly TestFiles.TempFolder _folder = TestFiles.NewFolder();
    private readonly JobViewModel _job;
    private readonly RunViewModel _run;
    private readonly SweepViewModel _sweep;

    public RunBarViewModelTests()
    {
        var activity = new MachineActivity();
        var machine = new MachineViewModel(new MachineConnectionFactory(new SimulatorOptions()), MachineProfile.Default, activity);
        _job = new JobViewModel(new ImageService(), MachineProfile.Default, activity);
        var store = Substitute.For<IRunLogStore>();
        store.Folder.Returns(_folder.Path);
        var log = new LogViewModel(new RunLogFolder(Path.Combine(_folder.Path, "logs")), Substitute.For<IFileAccess>(), _job);
        _run = new RunViewModel(new EngraveRunService(), _job, machine, log, TimeProvider.System);
        _sweep = new SweepViewModel(_job, machine, store, TimeProvider.System) { Labels = false, Columns = string.Empty, Rows = "speed=0.5,1" };
    }

    [Fact]
    public void StartCommand_SweepShownOnTheStage_StartsTheSweep()
    {
        var bar = new RunBarViewModel(_run, _sweep);
        Assert.Same(_run.StartCommand, bar.StartCommand);

        _sweep.ShowOnStage = true;

        Assert.True(bar.RunsSweep);
        Assert.Same(_sweep.RunSweepCommand, bar.StartCommand);
        Assert.False(bar.CanAbort);
    }

    [Fact]
    public void StartCommand_NoSweep_StartsTheJob()
    {
        var bar = new RunBarViewModel(_run);

        Assert.False(bar.RunsSweep);
        Assert.False(bar.Sweeping);
        Assert.Same(_run.StartCommand, bar.StartCommand);
        Assert.Equal(_run.Fraction, bar.Fraction);
    }

    public void Dispose() => _folder.Dispose();
}
