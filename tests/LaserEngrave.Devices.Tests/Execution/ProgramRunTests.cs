using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Jobs;
using LaserEngrave.Core.Planning;
using LaserEngrave.Core.Vectors;
using LaserEngrave.Devices.Execution;

namespace LaserEngrave.Devices.Tests.Execution;

/// <summary>
/// The executor runs the job's program: on the twin, a dot job's and a drawing's run do the program's steps in order, a
/// stop point is the index of the step under way, and a resume does the program's steps from it (its estimate the
/// program's from there).
/// </summary>
public class ProgramRunTests
{
    [Fact(Timeout = 120_000)]
    public async Task RunAsync_DotJobAbortedThenResumed_EachRunFiresTheProgramsStepsFromItsStopPoint()
    {
        var ct = TestContext.Current.CancellationToken;
        await using var run = SimulatedRun.Create();
        var job = TestJobs.FromMask(
            TestJobs.RandomMask(seed: 5, 12, 6),
            1,
            new PlanOptions(),
            process: ProcessSettings.Default with { Mode = PlanMode.Dots, PulsesPerDot = 2 });
        var program = ((DotJob)EngraveJob.Of(job)).Program();
        var executor = run.Executor(job);
        var first = new List<(long, long, long)>();
        executor.MoveCompleted += (_, e) =>
        {
            first.Add((e.MoveIndex, e.Move.X1, e.Move.Y1));
            if (e.MoveIndex == 9)
            {
                executor.Abort();
            }
        };

        var aborted = await run.Do(() => executor.RunAsync(ct));
        var stop = Assert.IsType<RunStopPoint>(aborted.StopPoint);
        var resumedExecutor = run.Executor(job, new RunOptions { ResumeFrom = stop });
        var second = new List<(long, long, long)>();
        resumedExecutor.MoveCompleted += (_, e) => second.Add((e.MoveIndex, e.Move.X1, e.Move.Y1));
        var resumed = await run.Do(() => resumedExecutor.RunAsync(ct));

        Assert.Equal(10, stop.MoveIndex);
        Assert.Equal(program.Steps().Take(10).Select(s => (s.Index, s.X, s.Y)), first);
        Assert.True(resumed.Outcome == RunOutcome.Completed, $"{resumed.Outcome}: {resumed.FaultMessage}");
        Assert.Equal(program.Steps(10).Select(s => (s.Index, s.X, s.Y)), second);
        Assert.Equal(job.Dots!.Estimate.TotalSeconds - program.SecondsBefore(10), resumed.EstimatedEngravingSeconds, 9);

        // Every dot fired once with its burst's pulses, none twice, none while moving.
        var report = run.Analyze(job);
        Assert.Equal(program.Steps().Count() * 2, report.Pulses);
        Assert.Equal(0, report.PulsesWhileMoving);
    }

    [Fact(Timeout = 120_000)]
    public async Task RunAsync_DrawingAbortedThenResumed_EachRunBurnsTheProgramsStrokesFromItsStopPoint()
    {
        var ct = TestContext.Current.CancellationToken;
        await using var run = SimulatedRun.Create();
        var drawing = PreparedDrawing.Prepare(
            new JobSpec { ImagePath = TestJobs.AssetPath(Path.Combine("drawings", "hexagons.dxf")), Size = SizeSpec.Width(4), Origin = new OriginMm(5, 5) },
            VectorOptions.Default);
        var program = ((DrawingJob)EngraveJob.Of(drawing)).Program();
        var executor = new RunExecutor(run.Stage, run.Gate, drawing, run.Time);
        var first = new List<Move>();
        executor.MoveCompleted += (_, e) => first.Add(e.Move);
        executor.ProgressChanged += (_, p) =>
        {
            if (p.RowsDone == 3)
            {
                executor.Abort();
            }
        };

        var aborted = await run.Do(() => executor.RunAsync(ct));
        var stop = Assert.IsType<RunStopPoint>(aborted.StopPoint);
        var resumedExecutor = new RunExecutor(run.Stage, run.Gate, drawing, run.Time, new RunOptions { ResumeFrom = stop });
        var second = new List<Move>();
        resumedExecutor.MoveCompleted += (_, e) => second.Add(e.Move);
        var resumed = await run.Do(() => resumedExecutor.RunAsync(ct));

        Assert.Equal(3, stop.MoveIndex);
        Assert.Equal(Segments(program.Steps().Take(3)), first);
        Assert.True(resumed.Outcome == RunOutcome.Completed, $"{resumed.Outcome}: {resumed.FaultMessage}");
        Assert.Equal(Segments(program.Steps(3)), second);
        Assert.Equal(program.SecondsFrom(3), resumed.EstimatedEngravingSeconds, 9);
        Assert.Equal(program.StrokeCount, resumed.RowsDone);
        Assert.Equal(drawing.Plan.Paths.Count, resumed.RunsDone);
    }

    // Each stroke's burned path, vertex to vertex, with the stroke's index as its row (what the run reports as done).
    private static List<Move> Segments(IEnumerable<DrawingStep> steps) =>
    [
        .. steps.SelectMany(s => s.Stroke.Path.Points.Zip(s.Stroke.Path.Points.Skip(1), (a, b) => new Move(MoveKind.Burn, a.X, a.Y, b.X, b.Y, s.Index))),
    ];
}
