using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Jobs;
using LaserEngrave.Core.Logging;
using LaserEngrave.Devices.Execution;
using LaserEngrave.Simulator.Burn;

namespace LaserEngrave.Devices.Tests.Execution;

/// <summary>A run of layers stopped in its second layer and continued: the rest of that layer and the later ones burn, the first does not again.</summary>
public sealed class LayeredResumeTests
{
    // Three layers apart on the stage, so the twin's trace shows which one the laser burned.
    private static readonly (double X, double Y, double W) First = (5, 5, 4);

    private static LayeredJob Job() => LayeredJob.Prepare(
        [
            new JobLayer { Name = "hexagons", Source = TestJobs.AssetPath(Path.Combine("drawings", "hexagons.dxf")), Mode = LayerMode.Outline, WidthMm = First.W, Origin = new OriginMm(First.X, First.Y) },
            new JobLayer { Name = "logo", Source = TestJobs.AssetPath("qr-code.bmp"), Mode = LayerMode.Raster, WidthMm = 1.5, Origin = new OriginMm(20, 20) },
            new JobLayer { Name = "cut", Source = TestJobs.AssetPath(Path.Combine("drawings", "layers.svg")), DrawingLayer = "cut", Mode = LayerMode.Outline, WidthMm = 6, Origin = new OriginMm(35, 35), Passes = 2 },
        ],
        MachineProfile.Default);

    private static EngraveSession Session(SimulatedRun run, LayeredJob job, RecordingLog log, LayerResumePoint? resume = null, bool inspect = false) => new(
        new EngraveMachine(run.Stage, run.Gate, run.Time, "simulator", "simulator") { Simulated = true, Inspector = inspect ? new BurnInspector(run.Machine) : null },
        job,
        new EngraveSessionOptions { Log = log, ResumeLayers = resume });

    /// <summary>Where the spot was, mm, every 0.5 ms the laser was on since the simulator started.</summary>
    private static List<(double X, double Y)> LaserOnSpots(SimulatedRun run)
    {
        var recorder = run.Machine.Recorder;
        var um = run.Machine.Profile.X.MicrostepUm / 1000;
        var vm = run.Machine.Profile.Y.MicrostepUm / 1000;
        var spots = new List<(double, double)>();
        foreach (var (from, to) in recorder.LaserOnIntervals(run.Machine.NowSeconds))
        {
            for (var t = from; t <= to; t += 0.0005)
            {
                spots.Add((recorder.X.PositionAt(t) * um, recorder.Y.PositionAt(t) * vm));
            }
        }

        return spots;
    }

    private static bool InFirst((double X, double Y) p) => p.X >= First.X - 0.05 && p.X <= First.X + First.W + 0.05 && p.Y >= First.Y - 0.05 && p.Y <= First.Y + First.W + 0.05;

    [Fact(Timeout = 180_000)]
    public async Task ResumeLayers_AbortedInLayerTwo_BurnsTheRestOfItAndTheLaterLayersButNotLayerOneAgain()
    {
        var ct = TestContext.Current.CancellationToken;
        var job = Job();
        var stoppedLog = new RecordingLog();
        await using (var run = SimulatedRun.Create())
        {
            EngraveSession? session = null;
            var aborted = 0;
            session = Session(run, job, stoppedLog);
            var progress = new SynchronousProgress(p =>
            {
                if (p.Layer == 2 && p.MovesDone >= 100 && Interlocked.Exchange(ref aborted, 1) == 0)
                {
                    _ = Task.Delay(TimeSpan.FromMilliseconds(50), run.Time).ContinueWith(_ => session.Abort(), run.Loop);
                }
            });

            var stopped = await session.RunAsync(progress, ct);

            Assert.Equal(RunState.Aborted, stopped.State);
            Assert.Contains(LaserOnSpots(run), InFirst);
            Assert.False(run.Machine.Gate.IsFiring);
        }

        var record = Assert.Single(stoppedLog.Records);
        Assert.Equal([RunOutcome.Completed, RunOutcome.Aborted, null], record.Layers!.Select(l => l.Outcome));
        var resume = RunReplay.ResumePoint(record);
        Assert.Equal((1, 0), (resume.Layer, resume.PassesDone));
        Assert.NotNull(resume.StopPoint);

        var resumedLog = new RecordingLog();
        var reports = new List<EngraveProgress>();
        await using (var run = SimulatedRun.Create())
        {
            var session = Session(run, job, resumedLog, resume);
            var result = await session.RunAsync(new SynchronousProgress(reports.Add), ct);

            Assert.Equal(RunState.Completed, result.State);
            Assert.Equal(3, session.Passes);
            var spots = LaserOnSpots(run);
            Assert.NotEmpty(spots);
            Assert.DoesNotContain(spots, InFirst);
        }

        var resumed = Assert.Single(resumedLog.Records);
        Assert.True(resumed.Resumed);
        Assert.Equal(RunOutcome.Completed, resumed.Outcome);
        Assert.Equal([2, 3], reports.Select(r => r.Layer).Distinct());

        // Each layer counts its own passes: layer 2 (one pass) is "pass 1 of 1", not "pass 1 of 3" of the passes summed.
        Assert.All(reports.Where(r => r.Layer == 2), r => Assert.Equal((1, 1), r.PassInLayer));
        Assert.Equal([(1, 2), (2, 2)], reports.Where(r => r.Layer == 3).Select(r => r.PassInLayer).Distinct());
        Assert.All(resumed.Layers!, l => Assert.Equal((RunOutcome.Completed, l.Passes), (l.Outcome!.Value, l.PassesDone)));
        Assert.Equal((0, 0, true), (resumed.Layers![0].EngravingSeconds, resumed.Layers[0].LaserOnSeconds, resumed.Layers[0].CompletedBefore));

        // The layer cut mid-run goes on from its stop point: less of it is burned than in a whole pass.
        Assert.InRange(resumed.Layers[1].EngravingSeconds, 0.1, 0.99 * job.Layers[1].EngravingSeconds);

        // Resuming the resumed run's log finds nothing left.
        Assert.Throws<RunLogException>(() => RunReplay.ResumePoint(resumed));
    }

    [Fact(Timeout = 180_000)]
    public async Task ResumeLayers_StoppedInTheSecondPassOfTheLastLayer_RunsOnlyThatPass()
    {
        var job = Job();
        var record = new RecordingLog();
        await using var run = SimulatedRun.Create();
        var session = Session(run, job, record, new LayerResumePoint(2, 1, null));

        var result = await session.RunAsync(null, TestContext.Current.CancellationToken);

        Assert.Equal(RunState.Completed, result.State);
        Assert.Equal(1, session.Passes);
        var layers = Assert.Single(record.Records).Layers!;
        Assert.Equal([1, 1, 2], layers.Select(l => l.PassesDone));
        Assert.InRange(layers[2].EngravingSeconds, 0.98 * job.Layers[2].EngravingSeconds, 1.02 * job.Layers[2].EngravingSeconds);
    }
}
