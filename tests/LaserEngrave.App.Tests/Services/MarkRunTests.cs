using LaserEngrave.App.Services;
using LaserEngrave.App.ViewModels;
using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Jobs;
using LaserEngrave.Core.Logging;
using LaserEngrave.Core.Marks;
using LaserEngrave.Devices.Execution;
using LaserEngrave.Simulator;
using NSubstitute;

namespace LaserEngrave.App.Tests.Services;

/// <summary>Marks made in the Mark panel and run from the Layers on the in-process simulator: the counter advances only when the run completes.</summary>
public sealed class MarkRunTests : IAsyncDisposable
{
    private readonly TestFiles.TempFolder _folder = TestFiles.NewFolder();
    private readonly IRunLogStore _store = Substitute.For<IRunLogStore>();
    private readonly MachineViewModel _machine;
    private readonly LayersViewModel _layers;
    private readonly RunViewModel _run;
    private readonly MarkViewModel _mark;
    private readonly MarkService _service;

    public MarkRunTests()
    {
        var activity = new MachineActivity();
        _machine = new MachineViewModel(new MachineConnectionFactory(new SimulatorOptions()), MachineProfile.Default, activity);
        var job = new JobViewModel(new ImageService(), MachineProfile.Default, activity);
        _store.History().Returns([]);
        _store.Save(Arg.Any<RunRecord>()).Returns(new RunLogFiles("/logs/run.json", "/logs/run.txt"));
        _layers = new LayersViewModel(new JobFiles(new AppFolders(_folder.Path)), job, activity);
        _run = new RunViewModel(new EngraveRunService(), job, _machine, new LogViewModel(_store, Substitute.For<IFileAccess>(), job), TimeProvider.System, _layers);
        _service = new MarkService(new AppFolders(_folder.Path), () => MachineProfile.Default, TimeProvider.System);
        _mark = new MarkViewModel(_service, _layers.Open) { SizeMm = 0.6, Copies = 2, Columns = 2, Label = false };
    }

    private async Task MakeAndConnectAsync()
    {
        await _mark.MakeCommand.ExecuteAsync(null);
        Assert.True(_mark.JobFile is not null, _mark.Error ?? _mark.Verdict);
        Assert.Equal(2, _layers.Layers.Count);
        await _machine.ConnectCommand.ExecuteAsync(null);
        Assert.True(_run.StartCommand.CanExecute(null), _run.Error ?? _machine.Error);
    }

    [Fact]
    public async Task Make_CopiesPastTheTravel_OneLineNamesTheCopyAndThePanelsBoxesNothingOpens()
    {
        _mark.OriginXMm = 59;
        _mark.OriginYMm = 59;
        _mark.Copies = 10;
        _mark.Columns = 10;

        await _mark.MakeCommand.ExecuteAsync(null);

        Assert.Null(_mark.JobFile);
        Assert.StartsWith("copy 2 of 10 (number 2", _mark.Error ?? string.Empty, StringComparison.Ordinal);
        Assert.Contains("past the stage's travel 0..60 mm (origin 59, 59): move origin to at most", _mark.Error, StringComparison.Ordinal);
        Assert.Contains("or give fewer columns or a smaller pitch", _mark.Error, StringComparison.Ordinal);
        Assert.DoesNotContain("originMm", _mark.Error, StringComparison.Ordinal);
    }

    [Fact(Timeout = 120_000)]
    public async Task Start_MarksRunToCompletion_CounterAdvancesPastTheirNumbers()
    {
        await MakeAndConnectAsync();

        await _run.StartCommand.ExecuteAsync(null);

        Assert.Equal(RunState.Completed, _run.State);
        Assert.Equal(3, _service.NextNumber());
        Assert.Equal(3, _mark.NextNumber);
        _store.Received(1).Save(Arg.Is<RunRecord>(r => r.Layers!.Select(l => l.Name).SequenceEqual(new[] { "Data Matrix \"S-001\"", "Data Matrix \"S-002\"" })));
    }

    [Fact(Timeout = 120_000)]
    public async Task Start_AgainAfterTheMarksCompleted_RefusedNamingTheBurnedNumbers()
    {
        await MakeAndConnectAsync();
        await _run.StartCommand.ExecuteAsync(null);
        Assert.Equal(RunState.Completed, _run.State);

        await _run.StartCommand.ExecuteAsync(null);

        Assert.Equal(RunState.Failed, _run.State);
        Assert.Contains("its marks carry the numbers 1..2, which a completed run has burned already", _run.Error, StringComparison.Ordinal);
        _store.Received(1).Save(Arg.Any<RunRecord>());
        Assert.Equal(3, _service.NextNumber());
    }

    [Fact(Timeout = 120_000)]
    public async Task Start_JobFileWithAnImageAndAMarkLayer_BurnsTheNumberedTextAndAdvancesTheCounter()
    {
        var image = Path.Combine(_folder.Path, "logo.bmp");
        File.Copy(TestFiles.Asset("qr-code.bmp"), image);
        var job = Path.Combine(_folder.Path, "plate.json");
        File.WriteAllText(job, """
            { "layers": [
              { "name": "logo", "source": "logo.bmp", "widthMm": 0.5, "originMm": [5, 5] },
              { "mark": { "text": "S-{n:000}", "textHeightMm": 0.2, "originMm": [5, 6] } }
            ] }
            """);

        Assert.True(_layers.Open(job), _layers.FileError);
        Assert.Equal(["logo", "text \"S-001\""], _layers.Layers.Select(l => l.Name));
        await _machine.ConnectCommand.ExecuteAsync(null);
        await _run.StartCommand.ExecuteAsync(null);

        Assert.Equal(RunState.Completed, _run.State);
        Assert.Equal(2, _service.NextNumber());
        _store.Received(1).Save(Arg.Is<RunRecord>(r => r.JobFile!.Marks!.FirstNumber == 1 && r.Layers![1].Name == "text \"S-001\""));
    }

    [Fact(Timeout = 120_000)]
    public async Task Start_MarksAborted_CounterKeepsItsNumberUntilTheContinueCompletes()
    {
        await MakeAndConnectAsync();
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
        Assert.Equal(1, _service.NextNumber());

        await _run.ContinueCommand.ExecuteAsync(null);

        Assert.Equal(RunState.Completed, _run.State);
        Assert.Equal(3, _service.NextNumber());
        Assert.Equal(3, _mark.NextNumber);
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
