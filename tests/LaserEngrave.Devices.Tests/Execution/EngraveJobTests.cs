using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Jobs;
using LaserEngrave.Core.Planning;
using LaserEngrave.Core.Sweeps;
using LaserEngrave.Core.Vectors;
using LaserEngrave.Devices.Execution;

namespace LaserEngrave.Devices.Tests.Execution;

/// <summary>Issue 23: one closed job hierarchy; the session and the executor each take it through one constructor.</summary>
public sealed class EngraveJobTests
{
    private static PreparedJob Qr(PlanMode mode = PlanMode.Raster) =>
        TestJobs.FromAsset("qr-code.bmp", 2, PlanOptions.Default, ProcessSettings.Default with { Mode = mode });

    private static PreparedDrawing Hexagons() => PreparedDrawing.Prepare(
        new JobSpec { ImagePath = TestJobs.AssetPath(Path.Combine("drawings", "hexagons.dxf")), Size = SizeSpec.Width(4), Origin = TestJobs.Origin, Passes = 2 },
        VectorOptions.Default);

    private static LayeredJob Layers() => LayeredJob.Prepare(
        [
            new JobLayer { Name = "hexagons", Source = TestJobs.AssetPath(Path.Combine("drawings", "hexagons.dxf")), Mode = LayerMode.Outline, WidthMm = 4, Origin = new OriginMm(5, 5) },
            new JobLayer { Name = "logo", Source = TestJobs.AssetPath("qr-code.bmp"), Mode = LayerMode.Raster, WidthMm = 1.5, Origin = new OriginMm(20, 20), Passes = 3 },
        ],
        MachineProfile.Default);

    private static SweepPlan Sweep() => SweepPlan.Build(new SweepSpec
    {
        Rows = SweepAxis.Parse("speed=0.5,2", "--rows"),
        Columns = SweepAxis.Parse("frequency=500,1000,2000", "--columns"),
        CellMm = 0.3,
        SpacingMm = 0.2,
        PitchUm = 50,
        Origin = new OriginMm(5, 5),
        Process = ProcessSettings.Default,
    });

    [Fact]
    public void Of_EachKind_TheKindItsPartsAndPasses()
    {
        var raster = EngraveJob.Of(Qr());
        var dots = EngraveJob.Of(Qr(PlanMode.Dots));
        var drawing = EngraveJob.Of(Hexagons());
        var layers = EngraveJob.Of(Layers());
        var sweep = SweepJob.Of(Sweep());

        Assert.IsType<RasterJob>(raster);
        Assert.Same(((DotJob)dots).Prepared.Dots, ((DotJob)dots).Plan);
        Assert.Equal((1, 2), (drawing.Parts.Count, drawing.Passes));
        Assert.Equal((2, 4, "logo"), (layers.Parts.Count, layers.Passes, layers.Parts[1].Layer.Name));

        // A sweep of 2 x 3 cells is a job of 6 cells, each a raster job of its own.
        Assert.Equal(6, sweep.Cells.Count);
        Assert.All(sweep.Cells, c => Assert.IsType<RasterJob>(c));
        Assert.Equal(sweep.Plan.EstimatedSeconds > 0, sweep.EstimatedSeconds > 0);
    }

    [Fact]
    public async Task Constructors_LayersOrSweepWhereOneImageIsRun_RefusedNamingWhereTheyRun()
    {
        await using var run = SimulatedRun.Create();
        var machine = new EngraveMachine(run.Stage, run.Gate, run.Time, "simulator", "simulator");

        var executor = Assert.Throws<ArgumentException>(() => new RunExecutor(run.Stage, run.Gate, EngraveJob.Of(Layers()), run.Time));
        var session = Assert.Throws<ArgumentException>(() => new EngraveSession(machine, SweepJob.Of(Sweep())));

        Assert.Contains("EngraveSession", executor.Message, StringComparison.Ordinal);
        Assert.Contains("SweepSession", session.Message, StringComparison.Ordinal);
    }
}
