using LaserEngrave.App.Services;
using LaserEngrave.App.ViewModels;
using LaserEngrave.Core.Geometry;
using LaserEngrave.Devices.Abstractions;
using NSubstitute;
using NSubstitute.ExceptionExtensions;

namespace LaserEngrave.App.Tests.ViewModels;

public sealed class RunViewModelTests
{
    private readonly Fakes _fakes = new();
    private readonly IRunService _runs = Substitute.For<IRunService>();
    private readonly IRunLogStore _store = Substitute.For<IRunLogStore>();
    private readonly MachineViewModel _machine;
    private readonly JobViewModel _job;
    private readonly LogViewModel _log;
    private readonly RunViewModel _run;

    public RunViewModelTests()
    {
        _machine = new MachineViewModel(_fakes.Factory, MachineProfile.Default);
        _job = new JobViewModel(new ImageService(), MachineProfile.Default);
        var moves = new TestMovesViewModel(_machine, _job);
        _log = new LogViewModel(_store, Substitute.For<IFileAccess>(), _job);
        _run = new RunViewModel(_runs, _job, _machine, moves, _log, TimeProvider.System);
        _store.History().Returns([]);
    }

    private async Task ReadyAsync()
    {
        _job.LoadImage(TestFiles.Asset("qr-code.bmp"));
        await _machine.ConnectCommand.ExecuteAsync(null);
    }

    [Fact]
    public async Task Start_NoImage_ErrorAndNoRun()
    {
        await _machine.ConnectCommand.ExecuteAsync(null);

        await _run.StartCommand.ExecuteAsync(null);

        Assert.Contains("no job planned", _run.Error, StringComparison.Ordinal);
        await _runs.DidNotReceive().RunAsync(Arg.Any<RunRequest>(), Arg.Any<IProgress<RunProgress>>(), Arg.Any<CancellationToken>());
    }

    [Fact]
    public async Task Start_NotConnected_ErrorAndNoRun()
    {
        _job.LoadImage(TestFiles.Asset("qr-code.bmp"));

        await _run.StartCommand.ExecuteAsync(null);

        Assert.Contains("not connected", _run.Error, StringComparison.Ordinal);
        await _runs.DidNotReceive().RunAsync(Arg.Any<RunRequest>(), Arg.Any<IProgress<RunProgress>>(), Arg.Any<CancellationToken>());
    }

    [Fact]
    public async Task Start_JobOutsideTravel_ErrorAndNoRun()
    {
        await ReadyAsync();
        _job.OriginYMm = 57;

        await _run.StartCommand.ExecuteAsync(null);

        Assert.Contains("outside the stage's travel", _run.Error, StringComparison.Ordinal);
        await _runs.DidNotReceive().RunAsync(Arg.Any<RunRequest>(), Arg.Any<IProgress<RunProgress>>(), Arg.Any<CancellationToken>());
    }

    [Fact]
    public async Task Start_RunCompletes_CompletedAndLogged()
    {
        await ReadyAsync();
        _log.SampleId = "S-17";
        _log.Notes = "first try";
        _runs.RunAsync(Arg.Any<RunRequest>(), Arg.Any<IProgress<RunProgress>>(), Arg.Any<CancellationToken>())
            .Returns(c =>
            {
                c.Arg<IProgress<RunProgress>>().Report(new RunProgress(10, 10, 5, 5, 1, 123, 456, false));
                return Task.CompletedTask;
            });

        await _run.StartCommand.ExecuteAsync(null);

        Assert.Equal(RunState.Completed, _run.State);
        Assert.Equal(1, _run.Fraction);
        Assert.Equal(123, _run.Progress!.XMicrosteps);
        _store.Received(1).Save(Arg.Is<RunRecord>(r => r.Outcome == "completed" && r.SampleId == "S-17" && r.Notes == "first try" && r.MovesDone == 10 && r.ImageSha256 != null));
        Assert.Equal("completed", _log.LastRun!.Outcome);
    }

    [Fact]
    public async Task Start_GateSilentDuringRun_FailedWithErrorAndLogged()
    {
        await ReadyAsync();
        _runs.RunAsync(Arg.Any<RunRequest>(), Arg.Any<IProgress<RunProgress>>(), Arg.Any<CancellationToken>())
            .ThrowsAsync(new DeviceTimeoutException("laser gate: no reply to FREQ 1000 within 500 ms"));

        await _run.StartCommand.ExecuteAsync(null);

        Assert.Equal(RunState.Failed, _run.State);
        Assert.Contains("no reply to FREQ", _run.Error, StringComparison.Ordinal);
        _store.Received(1).Save(Arg.Is<RunRecord>(r => r.Outcome == "failed" && r.Error!.Contains("FREQ")));
    }

    [Fact]
    public async Task Abort_WhileRunning_CancelsRunAndRecordsAborted()
    {
        await ReadyAsync();
        var started = new TaskCompletionSource();
        _runs.RunAsync(Arg.Any<RunRequest>(), Arg.Any<IProgress<RunProgress>>(), Arg.Any<CancellationToken>())
            .Returns(async c =>
            {
                started.SetResult();
                await Task.Delay(Timeout.Infinite, c.Arg<CancellationToken>());
            });
        var run = _run.StartCommand.ExecuteAsync(null);
        await started.Task.WaitAsync(TimeSpan.FromSeconds(10), TestContext.Current.CancellationToken);
        Assert.Equal(RunState.Running, _run.State);

        _run.AbortCommand.Execute(null);
        await run.WaitAsync(TimeSpan.FromSeconds(10), TestContext.Current.CancellationToken);

        Assert.Equal(RunState.Aborted, _run.State);
        _store.Received(1).Save(Arg.Is<RunRecord>(r => r.Outcome == "aborted"));
    }

    [Fact]
    public async Task PauseResume_WhileRunning_GateHeldThenReleased()
    {
        await ReadyAsync();
        var started = new TaskCompletionSource<RunRequest>();
        var finish = new TaskCompletionSource();
        _runs.RunAsync(Arg.Any<RunRequest>(), Arg.Any<IProgress<RunProgress>>(), Arg.Any<CancellationToken>())
            .Returns(async c =>
            {
                started.SetResult(c.Arg<RunRequest>());
                await finish.Task;
            });
        var run = _run.StartCommand.ExecuteAsync(null);
        var request = await started.Task.WaitAsync(TimeSpan.FromSeconds(10), TestContext.Current.CancellationToken);

        _run.PauseCommand.Execute(null);
        var paused = (_run.State, request.Pause.IsPaused);
        _run.ResumeCommand.Execute(null);
        var resumed = (_run.State, request.Pause.IsPaused);
        finish.SetResult();
        await run.WaitAsync(TimeSpan.FromSeconds(10), TestContext.Current.CancellationToken);

        Assert.Equal((RunState.Paused, true), paused);
        Assert.Equal((RunState.Running, false), resumed);
    }

    [Fact]
    public void Abort_NothingRunning_Harmless()
    {
        _run.AbortCommand.Execute(null);

        Assert.Equal(RunState.Idle, _run.State);
        Assert.True(_run.AbortCommand.CanExecute(null));
    }
}
