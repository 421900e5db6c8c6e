using LaserEngrave.App.Services;
using LaserEngrave.App.ViewModels;
using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Jobs;
using LaserEngrave.Core.Logging;
using LaserEngrave.Devices.Execution;
using LaserEngrave.Simulator;
using NSubstitute;

namespace LaserEngrave.App.Tests.Services;

/// <summary>The app's run, view-model to machine, on the in-process simulator in virtual time: the engine's session does the work, the view-model mirrors it.</summary>
public sealed class EngraveRunServiceTests : IAsyncDisposable
{
    private readonly TestFiles.TempFolder _folder = TestFiles.NewFolder();
    private readonly IRunLogStore _store = Substitute.For<IRunLogStore>();
    private readonly MachineViewModel _machine;
    private readonly JobViewModel _job;
    private readonly RunViewModel _run;
    private readonly List<RunState> _states = [];

    public EngraveRunServiceTests()
    {
        var activity = new MachineActivity();
        _machine = new MachineViewModel(new MachineConnectionFactory(new SimulatorOptions()), MachineProfile.Default, activity);
        _job = new JobViewModel(new ImageService(), MachineProfile.Default, activity);
        _store.History().Returns([]);
        _store.Save(Arg.Any<RunRecord>()).Returns(new RunLogFiles("/logs/run.json", "/logs/run.txt"));
        _run = new RunViewModel(new EngraveRunService(), _job, _machine, new LogViewModel(_store, Substitute.For<IFileAccess>(), _job), TimeProvider.System);
        _run.PropertyChanged += (_, e) =>
        {
            if (e.PropertyName == nameof(RunViewModel.State))
            {
                lock (_states)
                {
                    _states.Add(_run.State);
                }
            }
        };
    }

    private async Task ReadyAsync(int passes)
    {
        _job.LoadImage(TestFiles.WriteChecker(_folder.Path, 8, 4));
        _job.EditWidth(0.8);
        _job.OriginXMm = 0.5;
        _job.OriginYMm = 0.5;
        _job.Passes = passes;
        await _machine.ConnectCommand.ExecuteAsync(null);
        Assert.True(_run.StartCommand.CanExecute(null), _run.Error ?? _machine.Error);
    }

    [Fact(Timeout = 120_000)]
    public async Task Start_TwoPassesOnTheSimulator_CompletedMirroringTheEngineAndBothPassesLogged()
    {
        await ReadyAsync(passes: 2);

        await _run.StartCommand.ExecuteAsync(null);

        Assert.Equal(RunState.Completed, _run.State);
        Assert.Equal("Completed", _run.Bar.StateName);
        Assert.Equal(1, _run.Fraction);
        Assert.Equal((2, 2), (_run.Progress!.Pass, _run.Progress.Passes));
        Assert.Equal([RunState.Preflight, RunState.Running, RunState.Preflight, RunState.Running, RunState.Completed], Collapse(_states));
        _store.Received(1).Save(Arg.Is<RunRecord>(r => r.Outcome == RunOutcome.Completed && r.Passes == 2 && r.PassesDone == 2 && r.Simulated));
    }

    [Fact(Timeout = 120_000)]
    public async Task Start_TwiceOnOneSimulator_EachRunsBurnCheckedAlone()
    {
        await ReadyAsync(passes: 1);
        var records = new List<RunRecord>();
        _store.Save(Arg.Do<RunRecord>(records.Add)).Returns(new RunLogFiles("/logs/run.json", "/logs/run.txt"));

        await _run.StartCommand.ExecuteAsync(null);
        await _run.StartCommand.ExecuteAsync(null);

        Assert.Equal(2, records.Count);
        var (first, second) = (records[0].Simulation!, records[1].Simulation!);
        Assert.Equal((0L, 0L), (first.MissingPixels, first.ExtraPixels));
        Assert.Equal((0L, 0L), (second.MissingPixels, second.ExtraPixels));
        Assert.InRange(second.Pulses, first.Pulses * 0.99, first.Pulses * 1.01);
    }

    [Fact(Timeout = 120_000)]
    public async Task Abort_WhileRunning_EndsInTheEnginesAbortedWithTheLogWritten()
    {
        await ReadyAsync(passes: 1);
        var aborted = 0;
        _run.PropertyChanged += (_, e) =>
        {
            if (e.PropertyName == nameof(RunViewModel.Progress) && _run.Progress is { MovesDone: > 3 } && Interlocked.Exchange(ref aborted, 1) == 0)
            {
                _run.AbortCommand.Execute(null);
            }
        };

        await _run.StartCommand.ExecuteAsync(null);

        Assert.Equal(RunState.Aborted, _run.State);
        Assert.Contains(RunState.Aborting, _states);
        Assert.NotNull(_run.StoppedAt);
        _store.Received(1).Save(Arg.Is<RunRecord>(r => r.Outcome == RunOutcome.Aborted && r.StoppedAt != null));
    }

    [Fact(Timeout = 120_000)]
    public async Task Continue_LayersAbortedInLayerTwo_TheEngineGoesOnFromThereAndLayerOneIsNotBurnedAgain()
    {
        var layers = new LayersViewModel(new JobFiles(new AppFolders(_folder.Path)), _job, _machine.Activity);
        var run = new RunViewModel(new EngraveRunService(), _job, _machine, new LogViewModel(_store, Substitute.For<IFileAccess>(), _job), TimeProvider.System, layers);
        await ReadyAsync(passes: 1);
        foreach (var x in new[] { 0.5, 2, 3.5 })
        {
            _job.OriginXMm = x;
            Assert.True(layers.AddCurrent());
        }

        var records = new List<RunRecord>();
        _store.Save(Arg.Do<RunRecord>(records.Add)).Returns(new RunLogFiles("/logs/run.json", "/logs/run.txt"));
        var aborted = 0;
        run.PropertyChanged += (_, e) =>
        {
            if (e.PropertyName == nameof(RunViewModel.Progress) && run.Progress is { Layer: 2, MovesDone: > 3 } && Interlocked.Exchange(ref aborted, 1) == 0)
            {
                run.AbortCommand.Execute(null);
            }
        };

        await run.StartCommand.ExecuteAsync(null);
        Assert.Equal(RunState.Aborted, run.State);
        Assert.True(run.CanContinue, run.ContinueUnavailableReason);
        await run.ContinueCommand.ExecuteAsync(null);

        Assert.Equal(RunState.Completed, run.State);
        Assert.Equal(2, records.Count);
        Assert.Equal([RunOutcome.Completed, RunOutcome.Aborted, null], records[0].Layers!.Select(l => l.Outcome));
        var resumed = records[1];
        Assert.True(resumed.Resumed);
        Assert.Equal(2, resumed.Passes);
        Assert.All(resumed.Layers!, l => Assert.Equal(RunOutcome.Completed, l.Outcome));
        Assert.Equal((true, 0.0), (resumed.Layers![0].CompletedBefore, resumed.Layers[0].LaserOnSeconds));
        Assert.Null(resumed.Layers[0].Simulation);

        // Layer 2 went on from its stop point: the pixels the stopped run burned are not counted missing (issue 23), nothing extra; layer 3 whole.
        Assert.Equal(0, resumed.Layers[1].Simulation!.MissingPixels);
        Assert.Equal(0, resumed.Layers[1].Simulation!.ExtraPixels);
        Assert.Equal((0L, 0L), (resumed.Layers[2].Simulation!.MissingPixels, resumed.Layers[2].Simulation!.ExtraPixels));
    }

    public async ValueTask DisposeAsync()
    {
        if (_machine.Connection is { } connection)
        {
            await connection.DisposeAsync();
        }

        _folder.Dispose();
    }

    /// <summary>The states in order, each run of repeats as one.</summary>
    private static List<RunState> Collapse(List<RunState> states) =>
        states.Where((s, i) => i == 0 || states[i - 1] != s).ToList();
}
