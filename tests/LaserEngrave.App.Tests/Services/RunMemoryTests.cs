using LaserEngrave.App.Services;
using LaserEngrave.App.ViewModels;
using LaserEngrave.Core.Geometry;
using LaserEngrave.Devices.Execution;
using LaserEngrave.Simulator;
using NSubstitute;

namespace LaserEngrave.App.Tests.Services;

/// <summary>Alone in its collection: the heap it measures is then its own runs', not another test's.</summary>
[CollectionDefinition(nameof(RunMemoryTests), DisableParallelization = true)]
public sealed class RunMemoryCollection;

/// <summary>
/// The app's memory over many runs (issue 36, finding 12: 104 MB at start, 303 MB after about eight runs): what a run
/// leaves behind, its log kept in the history included, must not grow with every run.
/// </summary>
[Collection(nameof(RunMemoryTests))]
public sealed class RunMemoryTests : IAsyncDisposable
{
    private readonly TestFiles.TempFolder _folder = TestFiles.NewFolder();
    private readonly MachineViewModel _machine;
    private readonly JobViewModel _job;
    private readonly RunViewModel _run;

    public RunMemoryTests()
    {
        var activity = new MachineActivity();
        _machine = new MachineViewModel(new MachineConnectionFactory(new SimulatorOptions()), MachineProfile.Default, activity);
        _job = new JobViewModel(new ImageService(), MachineProfile.Default, activity);
        var log = new LogViewModel(new RunLogFolder(Path.Combine(_folder.Path, "logs")), Substitute.For<IFileAccess>(), _job);
        _run = new RunViewModel(new EngraveRunService(), _job, _machine, log, TimeProvider.System);
    }

    [Fact(Timeout = 600_000)]
    public async Task Start_TwentyRunsOfTheQr_MemoryAfterTheLastWithin50MbOfAfterTheFirst()
    {
        _job.LoadImage(TestFiles.Asset("qr-code.bmp"));
        _job.EditWidth(3);
        await _machine.ConnectCommand.ExecuteAsync(null);
        long afterFirst = 0;
        for (var run = 1; run <= 20; run++)
        {
            await _run.StartCommand.ExecuteAsync(null);
            Assert.True(_run.State == RunState.Completed, $"run {run}: {_run.State} {_run.Error}");
            if (run == 1)
            {
                afterFirst = Heap();
            }
        }

        var afterLast = Heap();
        Assert.True(afterLast - afterFirst < 50L << 20, $"{(afterLast - afterFirst) / (1 << 20)} MB more after 20 runs than after the first ({afterFirst >> 20} MB)");
    }

    private static long Heap()
    {
        GC.Collect(GC.MaxGeneration, GCCollectionMode.Forced, blocking: true, compacting: true);
        GC.WaitForPendingFinalizers();
        return GC.GetTotalMemory(forceFullCollection: true);
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
