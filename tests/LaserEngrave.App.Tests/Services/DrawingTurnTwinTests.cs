using LaserEngrave.App.Services;
using LaserEngrave.App.ViewModels;
using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Logging;
using LaserEngrave.Core.Vectors;
using LaserEngrave.Devices.Execution;
using LaserEngrave.Simulator;
using LaserEngrave.Simulator.Burn;
using NSubstitute;

namespace LaserEngrave.App.Tests.Services;

/// <summary>A drawing turned in the app is burned turned (issue 36): the twin's pulses lie on the upright drawing's strokes turned a quarter, not on the upright ones.</summary>
public sealed class DrawingTurnTwinTests : IAsyncDisposable
{
    private readonly IRunLogStore _store = Substitute.For<IRunLogStore>();
    private readonly MachineViewModel _machine = new(new MachineConnectionFactory(new SimulatorOptions()), MachineProfile.Default, new MachineActivity());

    [Fact(Timeout = 120_000)]
    public async Task Start_DrawingTurnedClockwise_TheTwinBurnsTheUprightStrokesTurnedAboutTheJobsCorner()
    {
        var job = new JobViewModel(new ImageService(), MachineProfile.Default, _machine.Activity);
        _store.History().Returns([]);
        _store.Save(Arg.Any<RunRecord>()).Returns(new RunLogFiles("/logs/run.json", "/logs/run.txt"));
        var run = new RunViewModel(new EngraveRunService(), job, _machine, new LogViewModel(_store, Substitute.For<IFileAccess>(), job), TimeProvider.System);
        Assert.True(job.LoadImage(TestFiles.Asset(Path.Combine("drawings", "scattered.dxf"))));
        job.EditWidth(3);
        job.OriginXMm = 2;
        job.OriginYMm = 2;
        var upright = job.Drawing!.Plan.Paths;
        Assert.True(job.Drawing.Plan.HeightMm < 2.5, $"the test needs a drawing wider than high, not {job.Drawing.Plan.HeightMm} mm high");

        job.Rotate(clockwise: true);
        await _machine.ConnectCommand.ExecuteAsync(null);
        await run.StartCommand.ExecuteAsync(null);

        Assert.Equal(RunState.Completed, run.State);

        // The upright strokes turned a quarter clockwise (y downwards: right goes down) with the box's corner kept.
        var points = upright.SelectMany(p => p.Points).ToList();
        var (minX, minY, maxY) = (points.Min(p => p.X), points.Min(p => p.Y), points.Max(p => p.Y));
        var turned = upright.Select(p => p with { Points = [.. p.Points.Select(q => new StagePoint(minX + (maxY - q.Y), minY + (q.X - minX)))] }).ToList();
        var twin = ((BurnInspector)_machine.Connection!.Inspector!).Machine;
        var onTurned = twin.Recorder.AnalyzePaths(turned, job.BurnSpeedMmPerS);
        var onUpright = twin.Recorder.AnalyzePaths(upright, job.BurnSpeedMmPerS);

        Assert.True(onTurned.Pulses > 100, $"{onTurned.Pulses} pulses");
        Assert.Equal(0, onTurned.OffPathPulses);
        Assert.True(onTurned.DeviationMaxUm < 5, $"{onTurned.DeviationMaxUm} µm from the turned strokes");
        Assert.True(onUpright.OffPathPulses > onTurned.Pulses / 2, $"only {onUpright.OffPathPulses} of {onUpright.Pulses} pulses off the upright strokes");
    }

    public async ValueTask DisposeAsync()
    {
        if (_machine.Connection is { } connection)
        {
            await connection.DisposeAsync();
        }
    }
}
