using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Jobs;
using LaserEngrave.Core.Planning;
using LaserEngrave.Core.Preview;
using LaserEngrave.Core.Tests.Vectors;
using LaserEngrave.Core.Vectors;

namespace LaserEngrave.Core.Tests.Preview;

/// <summary>The stage's picture of a job: its moves in mm, its boxes and rectangle, and the moves a run has burned.</summary>
public sealed class StagePictureTests
{
    private static string Qr => Path.Combine(Path.GetDirectoryName(TestDrawings.Folder)!, "qr-code.bmp");

    private static string Plate => Path.Combine(Path.GetDirectoryName(TestDrawings.Folder)!, "jobs", "plate.json");

    private static PreparedJob Image() =>
        PreparedJob.Prepare(new JobSpec { ImagePath = Qr, Size = SizeSpec.Width(4), Origin = new OriginMm(1.37, 2) });

    private static PreparedDrawing Drawing() =>
        PreparedDrawing.Prepare(new JobSpec { ImagePath = TestDrawings.File("hexagons.dxf"), Size = SizeSpec.Width(10), Origin = new OriginMm(3, 4) }, new VectorOptions());

    private static float[] Floats(byte[] bytes)
    {
        var floats = new float[bytes.Length / sizeof(float)];
        Buffer.BlockCopy(bytes, 0, floats, 0, bytes.Length);
        return floats;
    }

    [Fact]
    public void New_NoJob_NothingDrawn()
    {
        var picture = new StagePicture(null);

        Assert.Empty(picture.Moves);
        Assert.Equal(0, picture.Total);
        Assert.Empty(picture.Boxes);
        Assert.Null(picture.Rect);
        Assert.Equal(0, picture.DrawnDone(0, 5));
    }

    [Fact]
    public void New_Image_EveryPlanMoveInMmAndTheRectangleOfItsPixelGrid()
    {
        var image = Image();
        var picture = new StagePicture(EngraveJob.Of(image));
        var moves = image.Plan.Moves().ToList();
        var floats = Floats(picture.Moves);
        var um = image.Spec.Profile.X.MicrostepUm / 1000;
        var g = image.Geometry.Geometry;

        Assert.Equal(moves.Count, picture.Drawn);
        Assert.Equal(moves.Count, picture.Total);
        Assert.Equal((float)moves[3].Kind, floats[15]);
        Assert.Equal((float)(moves[3].X1 * um), floats[18]);
        Assert.Empty(picture.Boxes);
        Assert.Equal(new StageRect(g.EdgeX(0) * um, g.EdgeY(0) * um, (g.EdgeX(g.WidthPx) * um) - (g.EdgeX(0) * um), (g.EdgeY(g.HeightPx) * um) - (g.EdgeY(0) * um), true, image.Geometry.PitchUm / 1000), picture.Rect);
    }

    [Fact]
    public void DrawnDone_Image_ItsMovesDoneUpToThoseDrawn()
    {
        var picture = new StagePicture(EngraveJob.Of(Image()));

        Assert.Equal(7, picture.DrawnDone(0, 7));
        Assert.Equal(picture.Drawn, picture.DrawnDone(0, picture.Drawn + 10));
        Assert.Equal(0, picture.DrawnDone(1, 7));
    }

    [Fact]
    public void DrawnDone_Drawing_StrokesDoneAsTheMovesDrawnForThem()
    {
        var drawing = Drawing();
        var picture = new StagePicture(EngraveJob.Of(drawing));
        var ends = picture.Parts[0].StrokeEnds!;

        Assert.Equal(drawing.Schedule.Strokes.Count, ends.Length);
        Assert.Equal(0, picture.DrawnDone(0, 0));
        Assert.Equal(ends[0], picture.DrawnDone(0, 1));
        Assert.Equal(ends[^1], picture.DrawnDone(0, ends.Length + 3));
        Assert.Equal(picture.Drawn, ends[^1]);
        Assert.Equal(new StageRect(3, 4, drawing.Plan.WidthMm, drawing.Plan.HeightMm, true, drawing.Plan.MicrostepUm / 1000), picture.Rect);
    }

    [Fact]
    public void New_Layers_EachLayerNumberedInItsBoxAndItsMovesAfterTheOnesBefore()
    {
        var layered = LayeredJob.Prepare(JobFile.Load(Plate), MachineProfile.Default);
        var picture = new StagePicture(EngraveJob.Of(layered));

        Assert.Equal(["1 marks", "2 logo", "3 cut"], picture.Boxes.Select(b => b.Name));
        Assert.Equal((24.0, 22.0), (picture.Boxes[1].X, picture.Boxes[1].Y));
        Assert.Equal(picture.Boxes.Min(b => b.X), picture.Rect!.X);
        Assert.Equal(picture.Boxes.Max(b => b.Y + b.H) - picture.Boxes.Min(b => b.Y), picture.Rect.H);
        Assert.Equal([0, picture.Parts[0].Count, picture.Parts[0].Count + picture.Parts[1].Count], picture.Parts.Select(p => p.Start));
        Assert.Equal(picture.Parts.Sum(p => p.Count), picture.Drawn);

        // The logo's (a raster's) fifth move, then the cut's first stroke.
        Assert.Equal(picture.Parts[1].Start + 5, picture.DrawnDone(1, 5));
        Assert.Equal(picture.Parts[2].Start + picture.Parts[2].StrokeEnds![0], picture.DrawnDone(2, 1));
        Assert.Null(picture.Parts[1].StrokeEnds);
    }

    [Fact]
    public void LaserMm_BothAxesKnown_MicrostepsTimesTheirSize_ElseNone()
    {
        var profile = MachineProfile.Default;

        Assert.Equal((12345 * profile.X.MicrostepUm / 1000, 678 * profile.Y.MicrostepUm / 1000), StagePicture.LaserMm(12345, 678, profile));
        Assert.Null(StagePicture.LaserMm(null, 678, profile));
        Assert.Null(StagePicture.LaserMm(1, null, profile));
    }

    [Fact]
    public void PlanMoves_DotJob_ThePlansMovesNotItsDots()
    {
        var image = Image();
        var dots = PreparedJob.Prepare(image.Spec with { Process = image.Spec.Process with { Mode = PlanMode.Dots } });

        var (bytes, drawn, total) = StagePicture.PlanMoves(dots);

        Assert.Equal(dots.Plan.Moves().Count(), drawn);
        Assert.Equal(drawn, total);
        Assert.Equal(drawn * 5 * sizeof(float), bytes.Length);
    }
}
