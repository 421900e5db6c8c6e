using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Jobs;
using LaserEngrave.Core.Logging;
using LaserEngrave.Core.Planning;
using LaserEngrave.Core.Tests.Vectors;
using LaserEngrave.Core.Vectors;

namespace LaserEngrave.Core.Tests.Jobs;

/// <summary>What the front ends ask of a job, answered by the job type for every kind.</summary>
public sealed class EngraveJobTests
{
    private static string Qr => Path.Combine(Path.GetDirectoryName(TestDrawings.Folder)!, "qr-code.bmp");

    private static string Plate => Path.Combine(Path.GetDirectoryName(TestDrawings.Folder)!, "jobs", "plate.json");

    private static PreparedJob Image(double originXMm = 1, int passes = 1) =>
        PreparedJob.Prepare(new JobSpec { ImagePath = Qr, Size = SizeSpec.Width(4), Origin = new OriginMm(originXMm, 2), Passes = passes });

    private static PreparedDrawing Drawing(int passes = 1) =>
        PreparedDrawing.Prepare(new JobSpec { ImagePath = TestDrawings.File("hexagons.dxf"), Size = SizeSpec.Width(10), Origin = new OriginMm(3, 4), Passes = passes }, new VectorOptions());

    private static EngraveJob Layers() => EngraveJob.Of(LayeredJob.Prepare(JobFile.Load(Plate), MachineProfile.Default));

    [Fact]
    public void UnitOf_EachKind_StrokesForADrawingElseRows()
    {
        var layers = Layers();

        Assert.Equal("row", EngraveJob.Of(Image()).UnitOf(1));
        Assert.Equal("stroke", EngraveJob.Of(Drawing()).UnitOf(1));

        // The plate's layers: marks (outline), logo (raster), cut (outline); before the first report it counts rows.
        Assert.Equal(["stroke", "row", "stroke"], Enumerable.Range(1, 3).Select(layers.UnitOf));
        Assert.Equal("row", layers.UnitOf(0));
        Assert.Equal("row", layers.UnitOf(4));
    }

    [Fact]
    public void Programs_EachPartsProgramOfItsKind()
    {
        var image = Image();
        var dots = PreparedJob.Prepare(image.Spec with { Process = image.Spec.Process with { Mode = PlanMode.Dots } });

        var raster = Assert.IsType<RasterProgram>(Assert.Single(EngraveJob.Of(image).Programs));
        Assert.Same(image.Plan, raster.Plan);
        Assert.Equal(dots.Dots!.Program().Steps().Count(), Assert.IsType<DotProgram>(Assert.Single(EngraveJob.Of(dots).Programs)).Steps().Count());
        var drawing = Drawing();
        Assert.Same(drawing.Schedule.Program(), Assert.Single(EngraveJob.Of(drawing).Programs));

        // The plate's layers: marks (outline), logo (raster), cut (outline).
        Assert.Equal([typeof(DrawingProgram), typeof(RasterProgram), typeof(DrawingProgram)], Layers().Programs.Select(p => p.GetType()));
    }

    [Fact]
    public void Layers_OnlyAJobOfLayersNamesThem()
    {
        Assert.Null(EngraveJob.Of(Image()).Layers);
        Assert.Null(EngraveJob.Of(Drawing()).Layers);
        Assert.Equal(["marks", "logo", "cut"], Layers().Layers!.Select(l => l.Layer.Name));
    }

    [Fact]
    public void PassSeconds_SingleJob_EachPassItsEngravingAndSetup_AResumedRunItsStoppedPassOnly()
    {
        var image = Image(passes: 3);
        var drawing = Drawing(passes: 2);
        var stop = new RunStopPoint(0, 0);

        Assert.Equal(Enumerable.Repeat(image.Statistics.EngravingSeconds + image.Statistics.PassSetupSeconds, 3), EngraveJob.Of(image).PassSeconds());
        Assert.Equal(Enumerable.Repeat(drawing.Schedule.EstimatedSeconds + drawing.PassSetupSeconds, 2), EngraveJob.Of(drawing).PassSeconds());
        Assert.Single(EngraveJob.Of(image).PassSeconds(resumeFrom: stop));
    }

    [Fact]
    public void PassSeconds_ResumedLayers_TheLayersAndPassesDoneLeftOut()
    {
        var job = Layers();
        var all = job.PassSeconds();

        // marks 1 pass, logo 1, cut 2: resumed in cut after its first pass, one pass is left.
        Assert.Equal(job.Parts.Sum(p => p.Layer.Passes), all.Count);
        Assert.Equal(all.Skip(3), job.PassSeconds(resumeLayers: new LayerResumePoint(2, 1, null)));
        Assert.Equal(all.Skip(1), job.PassSeconds(resumeLayers: new LayerResumePoint(1, 0, null)));
    }

    [Fact]
    public void Planned_ImageAndDrawing_WhatTheirLogsCount()
    {
        var image = Image();
        var drawing = Drawing();

        var imageRecord = RunRecord.ForJob(image, "ab", DateTimeOffset.UnixEpoch);
        var drawingRecord = RunRecord.ForDrawing(drawing, "ab", DateTimeOffset.UnixEpoch);

        Assert.Equal((imageRecord.RowsTotal, imageRecord.RunsTotal), EngraveJob.Of(image).Planned);
        Assert.Equal((drawingRecord.RowsTotal, drawingRecord.RunsTotal), EngraveJob.Of(drawing).Planned);
    }

    [Fact]
    public void StartProblem_OutsideTheTravel_SaysSoInTheUsersWords()
    {
        var travel = MachineProfile.Default.X.TravelMm;

        Assert.Null(EngraveJob.Of(Image()).StartProblem);
        Assert.Null(EngraveJob.Of(Drawing()).StartProblem);
        Assert.Null(Layers().StartProblem);
        Assert.Equal("the job (4 x 4 mm at origin 59, 2 mm) does not fit the stage's travel (60 x 60 mm): move the origin or make it smaller", EngraveJob.Of(Image(originXMm: travel - 1)).StartProblem);
    }

    [Fact]
    public void FrameBox_Image_ItsPixelGridsOuterEdges_Drawing_TheBoxAroundItsPaths()
    {
        var image = Image();
        var drawing = Drawing();
        var g = image.Geometry.Geometry;
        var points = drawing.Plan.Paths.SelectMany(p => p.Points).ToList();

        Assert.Equal((g.EdgeX(0), g.EdgeY(0), g.EdgeX(g.WidthPx), g.EdgeY(g.HeightPx)), EngraveJob.Of(image).FrameBox);
        Assert.Equal((points.Min(p => p.X), points.Min(p => p.Y), points.Max(p => p.X), points.Max(p => p.Y)), EngraveJob.Of(drawing).FrameBox);
    }

    [Fact]
    public void FrameBox_Layers_AroundEveryLayer()
    {
        var job = Layers();
        var boxes = job.Parts.Select(p => p.FrameBox!.Value).ToList();

        Assert.Equal((boxes.Min(b => b.Left), boxes.Min(b => b.Top), boxes.Max(b => b.Right), boxes.Max(b => b.Bottom)), job.FrameBox);
    }

    [Fact]
    public void SmallestPixelUm_TheImagesPitch_NoneForADrawing()
    {
        var image = Image();
        var layers = Layers();

        Assert.Equal(image.Geometry.PitchUm, EngraveJob.Of(image).SmallestPixelUm);
        Assert.Null(EngraveJob.Of(Drawing()).SmallestPixelUm);
        Assert.Equal(layers.Parts.OfType<ImagePart>().Min(p => p.Image.Geometry.PitchUm), layers.SmallestPixelUm);
    }

    [Fact]
    public void Mask_OnlyASingleImageJobsMask()
    {
        var image = Image();
        var dots = PreparedJob.Prepare(image.Spec with { Process = image.Spec.Process with { Mode = PlanMode.Dots } });

        Assert.Same(image.Mask, EngraveJob.Of(image).Mask);
        Assert.Same(dots.Mask, EngraveJob.Of(dots).Mask);
        Assert.Null(EngraveJob.Of(Drawing()).Mask);
        Assert.Null(Layers().Mask);
    }
}
