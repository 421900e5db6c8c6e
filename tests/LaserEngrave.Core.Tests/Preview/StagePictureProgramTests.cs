using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Imaging;
using LaserEngrave.Core.Jobs;
using LaserEngrave.Core.Planning;
using LaserEngrave.Core.Preview;
using LaserEngrave.Core.Sweeps;
using LaserEngrave.Core.Tests.Vectors;
using LaserEngrave.Core.Vectors;

namespace LaserEngrave.Core.Tests.Preview;

/// <summary>
/// The stage's picture drawn from each part's program is the picture drawn from the plans (issue 23, item 1): the same
/// bytes, counts, part starts and stroke ends, on the samples, a job of layers, every drawing in assets/, a sweep and a
/// plan past the cap. The reference below is the picture as it was drawn from <c>RasterPlan.Moves()</c> and
/// <c>VectorSchedule.Strokes</c>.
/// </summary>
public sealed class StagePictureProgramTests
{
    private const int Cap = StagePicture.MaxDrawnMoves;

    private static string Assets => Path.GetDirectoryName(TestDrawings.Folder)!;

    // text.svg has only a <text>, which is refused as nothing to burn.
    public static TheoryData<string> Drawings() =>
        [.. Directory.GetFiles(TestDrawings.Folder).Where(DrawingReader.IsDrawing).Select(f => Path.GetFileName(f)).Where(f => f != "text.svg")];

    [Fact]
    public void New_Image_DrawnAsFromItsPlan()
    {
        var image = PreparedJob.Prepare(new JobSpec { ImagePath = Path.Combine(Assets, "qr-code.bmp"), Size = SizeSpec.Width(4), Origin = new OriginMm(1.37, 2) });

        AssertAsBefore(EngraveJob.Of(image));
    }

    [Fact]
    public void New_TextBannerRasterDotsAndPaper_DrawnAsFromTheirPlans()
    {
        var spec = new JobSpec { ImagePath = Path.Combine(Assets, "text-banner.png"), Size = SizeSpec.Width(20), Origin = new OriginMm(3, 3) };

        AssertAsBefore(EngraveJob.Of(PreparedJob.Prepare(spec)));
        AssertAsBefore(EngraveJob.Of(PreparedJob.Prepare(spec with { Process = spec.Process with { Mode = PlanMode.Dots } })));
        AssertAsBefore(EngraveJob.Of(PreparedJob.Prepare(spec with { Plan = spec.Plan with { Strategy = PlanStrategy.Paper } })));
    }

    [Fact]
    public void New_Layers_DrawnAsFromTheirPlans()
    {
        var layered = LayeredJob.Prepare(JobFile.Load(Path.Combine(Assets, "jobs", "plate.json")), MachineProfile.Default);

        AssertAsBefore(EngraveJob.Of(layered));
    }

    [Theory]
    [MemberData(nameof(Drawings))]
    public void New_Drawing_DrawnAsFromItsStrokes(string file)
    {
        var drawing = PreparedDrawing.Prepare(new JobSpec { ImagePath = TestDrawings.File(file), Size = SizeSpec.Width(20), Origin = new OriginMm(3, 4) }, new VectorOptions());

        AssertAsBefore(EngraveJob.Of(drawing));
    }

    [Fact]
    public void New_SweepWithLabels_DrawnAsFromItsCells()
    {
        var plan = SweepPlan.Build(new SweepSpec
        {
            Rows = SweepAxis.Parse("speed=0.5,2", "--rows"),
            Columns = SweepAxis.Parse("frequency=500,1000", "--columns"),
            Origin = new OriginMm(5, 5),
            CellMm = 1,
            SpacingMm = 0.5,
            PitchUm = 50,
            Labels = true,
        });

        AssertAsBefore(SweepJob.Of(plan));
    }

    [Fact]
    public void New_PlanOfMoreMovesThanDrawn_CappedAsFromItsPlan()
    {
        // One-pixel checks: every other pixel a burn run of its own, far more moves than the page draws.
        var mask = new BitMask(500, 500);
        for (var y = 0; y < mask.Height; y++)
        {
            for (var x = y % 2; x < mask.Width; x += 2)
            {
                mask[x, y] = true;
            }
        }

        var info = new ImageInfo("checks", ImageFormat.Bmp, 1, 2, mask.Width, mask.Height, 0, null, null, RowOrder.TopDown, "none", false);
        var job = PreparedJob.Prepare(new JobSpec { ImagePath = "checks.bmp", Size = SizeSpec.Width(50), Origin = new OriginMm(1, 1) }, info, mask);

        var picture = AssertAsBefore(EngraveJob.Of(job));

        Assert.Equal(Cap, picture.Drawn);
        Assert.True(picture.Total > Cap);
    }

    [Fact]
    public void RasterProgram_BurnedSegments_ThePlansBurnMoves()
    {
        var image = PreparedJob.Prepare(new JobSpec { ImagePath = Path.Combine(Assets, "text-banner.png"), Size = SizeSpec.Width(20), Origin = new OriginMm(3, 3) });
        var picture = new StagePicture(EngraveJob.Of(image));
        var floats = Floats(picture.Moves);
        var burns = image.Plan.Moves().Where(m => m.Kind == MoveKind.Burn).ToList();
        var um = image.Spec.Profile.X.MicrostepUm / 1000;
        var vm = image.Spec.Profile.Y.MicrostepUm / 1000;

        var drawn = Enumerable.Range(0, picture.Drawn).Where(i => floats[i * 5] == (float)MoveKind.Burn).Select(i => floats[((i * 5) + 1)..((i * 5) + 5)]).ToList();

        Assert.Equal(burns.Count, drawn.Count);
        Assert.All(burns.Zip(drawn), p => Assert.Equal([(float)(p.First.X0 * um), (float)(p.First.Y0 * vm), (float)(p.First.X1 * um), (float)(p.First.Y1 * vm)], p.Second));
    }

    private static StagePicture AssertAsBefore(EngraveJob job)
    {
        var picture = new StagePicture(job);
        var (bytes, drawn, total, parts) = Reference(job);

        Assert.Equal(drawn, picture.Drawn);
        Assert.Equal(total, picture.Total);
        Assert.Equal(bytes, picture.Moves);
        Assert.Equal(parts.Length, picture.Parts.Count);
        for (var i = 0; i < parts.Length; i++)
        {
            Assert.Equal((parts[i].Start, parts[i].Count), (picture.Parts[i].Start, picture.Parts[i].Count));
            Assert.Equal(parts[i].StrokeEnds, picture.Parts[i].StrokeEnds);
        }

        return picture;
    }

    private static float[] Floats(byte[] bytes)
    {
        var floats = new float[bytes.Length / sizeof(float)];
        Buffer.BlockCopy(bytes, 0, floats, 0, bytes.Length);
        return floats;
    }

    // The picture as drawn from the plans before the programs: every part's moves, each kept within what is left of the cap.
    private static (byte[] Bytes, int Drawn, long Total, StagePart[] Parts) Reference(EngraveJob job)
    {
        using var all = new MemoryStream();
        var parts = new List<StagePart>();
        var drawn = 0;
        long total = 0;
        foreach (var part in job.Parts)
        {
            int[]? ends = null;
            var (bytes, count, moves) = part is DrawingPart { Drawing: var drawing } ? DrawingMoves(drawing, out ends) : PlanMoves(((ImagePart)part).Image);
            var kept = Math.Max(0, Math.Min(count, Cap - drawn));
            all.Write(bytes, 0, kept * 5 * sizeof(float));
            parts.Add(new StagePart(drawn, kept, ends));
            drawn += kept;
            total += moves;
        }

        return (all.ToArray(), drawn, total, [.. parts]);
    }

    private static (byte[] Bytes, int Drawn, long Total) PlanMoves(PreparedJob job)
    {
        var um = Units.UmToMm(job.Spec.Profile.X.MicrostepUm);
        var vm = Units.UmToMm(job.Spec.Profile.Y.MicrostepUm);
        var values = new List<float>();
        var capped = false;
        foreach (var move in job.Plan.Moves())
        {
            if (values.Count >= Cap * 5)
            {
                capped = true;
                break;
            }

            values.AddRange([(float)move.Kind, (float)(move.X0 * um), (float)(move.Y0 * vm), (float)(move.X1 * um), (float)(move.Y1 * vm)]);
        }

        var drawn = values.Count / 5;
        return (Bytes(values), drawn, capped ? Math.Max(job.Statistics.Moves, drawn + 1L) : drawn);
    }

    private static (byte[] Bytes, int Drawn, long Total) DrawingMoves(PreparedDrawing drawing, out int[] strokeMoveEnds)
    {
        var um = Units.UmToMm(drawing.Spec.Profile.X.MicrostepUm);
        var vm = Units.UmToMm(drawing.Spec.Profile.Y.MicrostepUm);
        var values = new List<float>();
        var ends = new int[drawing.Schedule.Strokes.Count];
        var at = drawing.Plan.Start;
        var moves = 0;
        long total = 0;
        void Add(MoveKind kind, StagePoint a, StagePoint b)
        {
            if (a == b)
            {
                return;
            }

            total++;
            if (moves < Cap)
            {
                values.AddRange([(float)kind, (float)(a.X * um), (float)(a.Y * vm), (float)(b.X * um), (float)(b.Y * vm)]);
                moves++;
            }
        }

        foreach (var stroke in drawing.Schedule.Strokes)
        {
            var points = stroke.Path.Points;
            Add(MoveKind.Travel, at, stroke.RunUpStart);
            Add(MoveKind.Overscan, stroke.RunUpStart, points[0]);
            for (var k = 1; k < points.Count; k++)
            {
                Add(MoveKind.Burn, points[k - 1], points[k]);
            }

            Add(MoveKind.Overscan, points[^1], stroke.RestEnd);
            ends[stroke.Index] = moves;
            at = stroke.RestEnd;
        }

        strokeMoveEnds = ends;
        return (Bytes(values), moves, total);
    }

    private static byte[] Bytes(List<float> values)
    {
        var bytes = new byte[values.Count * sizeof(float)];
        Buffer.BlockCopy(values.ToArray(), 0, bytes, 0, bytes.Length);
        return bytes;
    }
}
