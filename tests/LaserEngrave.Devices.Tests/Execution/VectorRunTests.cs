using System.Globalization;
using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Jobs;
using LaserEngrave.Core.Vectors;
using LaserEngrave.Devices.Execution;
using LaserEngrave.Simulator;
using LaserEngrave.Simulator.Burn;

namespace LaserEngrave.Devices.Tests.Execution;

/// <summary>Vector strokes on the twin: each axis streaming its speed keeps the pulses on the path, evenly spaced, without dwells.</summary>
public class VectorRunTests
{
    [Theory(Timeout = 120_000)]
    [InlineData(0)]
    [InlineData(1)]
    [InlineData(17)]
    [InlineData(45)]
    [InlineData(90)]
    [InlineData(133)]
    [InlineData(200)]
    [InlineData(271)]
    public async Task RunAsync_StraightLineAtAnyAngle_WithinThreeMicrometres(double degrees)
    {
        var a = degrees * Math.PI / 180;
        var (x1, y1) = (2 + (1.5 * Math.Cos(a)), 2 + (1.5 * Math.Sin(a)));
        var drawing = TestDrawing.Svg($"<line x1=\"2\" y1=\"2\" x2=\"{F(x1)}\" y2=\"{F(y1)}\"/>");
        var (result, report, job) = await RunAsync(drawing, seed: 1);

        AssertOnPath(result, report, job);
    }

    [Theory(Timeout = 120_000)]
    [InlineData(0.5, 1)]
    [InlineData(0.5, 7)]
    [InlineData(2, 1)]
    public async Task RunAsync_Circle_WithinThreeMicrometresAndNoStop(double radiusMm, int seed)
    {
        var drawing = TestDrawing.Svg($"<circle cx=\"3\" cy=\"3\" r=\"{F(radiusMm)}\"/>");
        var (result, report, job) = await RunAsync(drawing, seed);

        AssertOnPath(result, report, job);
        Assert.Single(job.Schedule.Strokes);
    }

    [Theory(Timeout = 300_000)]
    [InlineData(1)]
    [InlineData(2)]
    public async Task RunAsync_FilledRectangle_EveryStrokeStartsWhereTheStageReportedIt(int seed)
    {
        // The scan lines' ends line up: the model has each stroke's X at rest where the next one's run-up starts, but
        // where the X axis really rests varies with the latencies. Trusting the model, the stroke's start drifted by
        // that spread stroke after stroke until a position query refused the run (text-as-paths.svg, 50 µm fill).
        var drawing = TestDrawing.Svg("<rect x=\"2\" y=\"2\" width=\"0.2\" height=\"1.5\"/>");
        var (result, report, job) = await RunAsync(drawing, seed, vector: VectorOptions.Default with { Fill = VectorFillMode.Fill, FillPitchUm = 20 });

        Assert.Contains(job.Schedule.Strokes.Skip(1), s => s.RunUpStart.X == job.Schedule.Strokes[s.Index - 1].RestEnd.X);
        AssertOnPath(result, report, job);
        Assert.InRange(report.DeviationMaxUm, 0, 1);
    }

    internal static async Task<(RunResult Result, PathReport Report, PreparedDrawing Job)> RunAsync(string drawingPath, int seed, VectorMotionOptions? motion = null, double? widthMm = null, VectorOptions? vector = null)
    {
        var spec = new JobSpec { ImagePath = drawingPath, Size = SizeSpec.Width(widthMm ?? 1), Origin = new OriginMm(5, 5) };
        vector ??= VectorOptions.Default;
        var job = widthMm is null ? PreparedDrawing.PrepareOwnSize(spec, vector, motion) : PreparedDrawing.Prepare(spec, vector, motion);
        await using var run = SimulatedRun.Create(new SimulatorOptions { Seed = seed });
        var result = await run.Do(() => new RunExecutor(run.Stage, run.Gate, job, run.Time).RunAsync(TestContext.Current.CancellationToken));
        var report = run.Machine.Recorder.AnalyzePaths(job.Plan.Paths, job.Spec.Process.BurnSpeedMmPerS);
        TestContext.Current.TestOutputHelper?.WriteLine(string.Create(
            CultureInfo.InvariantCulture,
            $"{Path.GetFileName(drawingPath)}: deviation mean {report.DeviationMeanUm:0.###} max {report.DeviationMaxUm:0.###} µm (model {job.Schedule.PredictedDeviationUm:0.###}), spacing {report.SpacingMinUm:0.###}..{report.SpacingMaxUm:0.###} mean {report.SpacingMeanUm:0.####} µm, dwells {report.DwellCount}, off path {report.OffPathPulses}, {report.Pulses} pulses, engraving {result.EngravingDuration.TotalSeconds:0.###} s estimated {result.EstimatedSeconds:0.###} s, strokes {job.Schedule.Strokes.Count}"));
        return (result, report, job);
    }

    internal static void AssertOnPath(RunResult result, PathReport report, PreparedDrawing job)
    {
        Assert.True(result.Outcome == RunOutcome.Completed, $"{result.Outcome}: {result.FaultMessage}");
        Assert.True(report.Pulses > 0);
        Assert.InRange(report.DeviationMaxUm, 0, 3);
        Assert.Equal(0, report.OffPathPulses);
        Assert.Equal(0, report.DwellCount);
        Assert.InRange(report.SpacingMinUm, report.ExpectedSpacingUm * 0.9, report.ExpectedSpacingUm * 1.1);
        Assert.InRange(report.SpacingMaxUm, report.ExpectedSpacingUm * 0.9, report.ExpectedSpacingUm * 1.1);
        Assert.InRange(result.EngravingDuration.TotalSeconds, job.Schedule.EstimatedSeconds * 0.98, job.Schedule.EstimatedSeconds * 1.02);
    }

    private static string F(double v) => v.ToString("0.######", CultureInfo.InvariantCulture);
}

/// <summary>Small SVG drawings in millimetres, written to the test's temporary folder.</summary>
internal static class TestDrawing
{
    private static readonly Lazy<string> Folder = new(() =>
    {
        var folder = Directory.CreateTempSubdirectory("le-vector-").FullName;
        AppDomain.CurrentDomain.ProcessExit += (_, _) =>
        {
            try
            {
                Directory.Delete(folder, recursive: true);
            }
            catch (IOException)
            {
                // Left for the system's temp cleaning.
            }
        };
        return folder;
    });

    public static string Svg(string body)
    {
        var path = Path.Combine(Folder.Value, $"{Guid.NewGuid():N}.svg");
        File.WriteAllText(path, $"<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"10mm\" height=\"10mm\" viewBox=\"0 0 10 10\">{body}</svg>");
        return path;
    }
}

/// <summary>The test drawings on the twin (assets/drawings), figures printed for docs/vectors.md.</summary>
[Trait("Category", "Figures")]
public class VectorDrawingFigures
{
    [Theory(Timeout = 600_000)]
    [InlineData("hexagons.dxf")]
    [InlineData("scattered.dxf")]
    [InlineData("curves.dxf")]
    [InlineData("every-command.svg")]
    public async Task RunAsync_TestDrawing_OnPathAndAsEstimated(string name)
    {
        var path = TestJobs.AssetPath(Path.Combine("drawings", name));
        var watch = System.Diagnostics.Stopwatch.StartNew();
        var (result, report, job) = await VectorRunTests.RunAsync(path, seed: 1, widthMm: 20);
        TestContext.Current.TestOutputHelper?.WriteLine($"wall {watch.Elapsed.TotalSeconds:0.00} s");
        VectorRunTests.AssertOnPath(result, report, job);
    }
}

/// <summary>Continuous strokes against a stop at every vertex (laser off for each stop), on the twin: both on the path, continuous much faster.</summary>
[Trait("Category", "Figures")]
public class VectorStopFigures
{
    [Fact(Timeout = 600_000)]
    public async Task RunAsync_CircleHalfMillimetre_ContinuousFasterThanStoppingAtEveryVertex()
    {
        var drawing = TestDrawing.Svg("<circle cx=\"3\" cy=\"3\" r=\"0.5\"/>");
        var (smooth, smoothReport, smoothJob) = await VectorRunTests.RunAsync(drawing, seed: 1);
        var (stops, stopsReport, stopsJob) = await VectorRunTests.RunAsync(drawing, seed: 1, new VectorMotionOptions { StopAtEveryVertex = true });

        VectorRunTests.AssertOnPath(smooth, smoothReport, smoothJob);
        VectorRunTests.AssertOnPath(stops, stopsReport, stopsJob);
        Assert.True(stops.EngravingDuration > 3 * smooth.EngravingDuration, $"{stops.EngravingDuration} against {smooth.EngravingDuration}");
    }
}
