using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Jobs;
using LaserEngrave.Core.Planning;
using LaserEngrave.Core.Vectors;

namespace LaserEngrave.Core.Tests.Vectors;

/// <summary>Jobs of layers: the job file, each layer's own settings, a drawing's layer placed where it is in the whole drawing.</summary>
public sealed class LayeredJobTests : IDisposable
{
    private readonly string folder = Path.Combine(Path.GetTempPath(), $"le-layers-{Guid.NewGuid():N}");

    public LayeredJobTests() => Directory.CreateDirectory(folder);

    private static string Plate => Path.Combine(Path.GetDirectoryName(TestDrawings.Folder)!, "jobs", "plate.json");

    [Fact]
    public void Load_PlateJob_LayersInOrderWithTheirOwnSettingsAndSourcesFromTheFilesFolder()
    {
        var layers = JobFile.Load(Plate);

        Assert.Equal(["marks", "logo", "cut"], layers.Select(l => l.Name));
        Assert.Equal([LayerMode.Outline, LayerMode.Raster, LayerMode.Outline], layers.Select(l => l.Mode));
        Assert.Equal(TestDrawings.File("layers.svg"), layers[0].Source);
        Assert.Equal(0.5, layers[0].SpeedMmPerS);
        Assert.Equal(500, layers[0].FrequencyHz);
        Assert.Equal(2, layers[2].Passes);
        Assert.Equal(new OriginMm(24, 22), layers[1].Origin);
    }

    [Fact]
    public void Save_PlateJobElsewhere_ReadsBackTheSameLayersWithSourcesRelativeToTheNewFile()
    {
        var layers = JobFile.Load(Plate);
        var saved = Path.Combine(folder, "sub", "plate-copy.json");
        Directory.CreateDirectory(Path.GetDirectoryName(saved)!);

        JobFile.Save(saved, layers);

        Assert.Equal(layers, JobFile.Load(saved));
        using var json = System.Text.Json.JsonDocument.Parse(File.ReadAllText(saved));
        Assert.All(json.RootElement.GetProperty("layers").EnumerateArray(), l => Assert.False(Path.IsPathRooted(l.GetProperty("source").GetString())));
    }

    [Fact]
    public void Save_EveryFieldSet_RoundTrips()
    {
        var layers = new List<JobLayer>
        {
            new() { Name = "fill \"a\"", Source = TestDrawings.File("hexagons.dxf"), Mode = LayerMode.Both, DrawingLayer = "0", WidthMm = 12.5, Origin = new OriginMm(1.25, 3), SpeedMmPerS = 0.75, FrequencyHz = 2500, Passes = 3, ToleranceUm = 0.5, FillPitchUm = 40 },
            new() { Name = "layer 2", Source = Path.Combine(Path.GetDirectoryName(TestDrawings.Folder)!, "qr-code.bmp"), Mode = LayerMode.Raster, WidthMm = 3 },
            new() { Name = "dithered", Source = Path.Combine(Path.GetDirectoryName(TestDrawings.Folder)!, "qr-code.bmp"), Mode = LayerMode.Raster, WidthMm = 2, Mask = new Core.Imaging.MaskOptions { ThresholdPercent = 30, Dither = Core.Imaging.DitherMethod.FloydSteinberg, Invert = true } },
        };
        var path = Path.Combine(folder, "job.json");

        JobFile.Save(path, layers);

        Assert.Equal(layers, JobFile.Load(path));
    }

    [Fact]
    public void Prepare_ImageLayerWithItsMask_TheMaskIsTheLayersAndADrawingRefusesOne()
    {
        var qr = Path.Combine(Path.GetDirectoryName(TestDrawings.Folder)!, "qr-code.bmp");
        var inverted = new JobLayer { Name = "inverted", Source = qr, Mode = LayerMode.Raster, WidthMm = 3, Mask = new Core.Imaging.MaskOptions { Invert = true } };
        var plain = inverted with { Mask = Core.Imaging.MaskOptions.Default };

        var job = LayeredJob.Prepare([plain, inverted], MachineProfile.Default);

        Assert.Equal(41 * 41, ((ImagePart)job.Layers[0]).Image.Mask.CountSet() + ((ImagePart)job.Layers[1]).Image.Mask.CountSet());
        var drawing = new JobLayer { Name = "d", Source = TestDrawings.File("hexagons.dxf"), Mode = LayerMode.Outline, Mask = new Core.Imaging.MaskOptions { Invert = true } };
        Assert.Equal("layer \"d\": thresholdPercent, dither and invert are for images", Assert.Throws<PlanException>(() => LayeredJob.Prepare([drawing], MachineProfile.Default)).Message);
    }

    [Theory]
    [InlineData("\"dither\": \"sierra\"", "dither \"sierra\" is not none, floyd-steinberg, atkinson or bayer")]
    [InlineData("\"thresholdPercent\": 120", "thresholdPercent 120: must be between 0 and 100")]
    [InlineData("\"invert\": 1", "\"invert\" must be true or false")]
    public void Load_BadMaskField_OneLineNamingTheLayerAndField(string field, string expected)
    {
        var path = Path.Combine(folder, "bad-mask.json");
        File.WriteAllText(path, $$"""{ "layers": [ { "name": "logo", "source": "x.bmp", "widthMm": 3, {{field}} } ] }""");

        var ex = Assert.Throws<PlanException>(() => JobFile.Load(path));

        Assert.Equal($"{path}: layer 1 \"logo\": {expected}", ex.Message);
    }

    [Fact]
    public void Prepare_PlateJob_EachLayerPlannedWithItsProcessAndTheEstimateAddsUpThePasses()
    {
        var job = LayeredJob.Prepare(JobFile.Load(Plate), MachineProfile.Default);

        Assert.Equal(0.5, ((DrawingPart)job.Layers[0]).Drawing.Spec.Process.BurnSpeedMmPerS);
        Assert.Equal(1, ((DrawingPart)job.Layers[2]).Drawing.Spec.Process.BurnSpeedMmPerS);
        Assert.IsAssignableFrom<ImagePart>(job.Layers[1]);
        // One homing: the first layer's whole run, then each later one from where the one before ended (less than alone).
        Assert.Equal(JobPart.RunSeconds(job.Layers).Sum(), job.EstimatedSeconds, 9);
        Assert.True(job.EstimatedSeconds < job.Layers.Sum(l => l.EstimatedSeconds));
        Assert.Equal(job.Layers.Sum(l => l.EngravingSeconds * l.Layer.Passes), job.EstimatedEngravingSeconds, 9);

        // The cut's two passes: twice the engraving, with the preflight before each.
        var cut = job.Layers[2];
        Assert.Equal(((DrawingPart)cut).Drawing.WholeRunSeconds(2), cut.EstimatedSeconds, 9);
        Assert.True(cut.EstimatedSeconds > 2 * cut.EngravingSeconds);
    }

    [Fact]
    public void Plan_OneLayerOfADrawing_OnlyItsPathsPlacedWhereTheyAreInTheWholeDrawing()
    {
        var whole = VectorPlanner.Plan(TestDrawings.File("layers.svg"), new VectorOptions { Origin = new OriginMm(10, 10) }, MachineProfile.Default);
        var mark = VectorPlanner.Plan(TestDrawings.File("layers.svg"), new VectorOptions { Origin = new OriginMm(10, 10), Layer = "mark" }, MachineProfile.Default);

        Assert.All(mark.Paths, p => Assert.Equal("mark", p.Layer));
        Assert.Equal(3, mark.Paths.Count);
        Assert.Equal(whole.Scale, mark.Scale);
        var cross = mark.Paths.SelectMany(p => p.Points).ToHashSet();
        var everything = whole.Paths.SelectMany(p => p.Points).ToHashSet();
        Assert.Subset(everything, cross);
    }

    [Fact]
    public void Plan_LayerTheDrawingDoesNotHave_OneLineNamingItsLayers()
    {
        var ex = Assert.Throws<DrawingException>(() => VectorPlanner.Plan(TestDrawings.File("layers.svg"), new VectorOptions { Layer = "engrave" }, MachineProfile.Default));

        Assert.Contains("no path on layer \"engrave\" (its layers: cut, mark)", ex.Message, StringComparison.Ordinal);
    }

    [Theory]
    [InlineData("""{"layers":[{"name":"a","source":"x.svg","speed":1}]}""", "layer 1: unknown field \"speed\"")]
    [InlineData("""{"layers":[{"name":"a"}]}""", "layer 1 \"a\": \"source\" (the image or drawing file) is missing")]
    [InlineData("""{"layers":[{"name":"a","source":"x.svg","mode":"hatch"}]}""", "mode \"hatch\" is not raster, outline, fill or both")]
    [InlineData("""{"layers":[{"name":"a","source":"x.svg","passes":0}]}""", "passes 0: must be 1..100 (burns of the plan over the same place)")]
    [InlineData("""{"layers":[{"name":"a","source":"x.svg","originMm":[1]}]}""", "\"originMm\" must be [x, y] in mm")]
    [InlineData("""{"layers":[]}""", "\"layers\" is empty")]
    [InlineData("""{"jobs":[]}""", "a job file is an object with \"layers\"")]
    public void Load_BadJobFile_OneLineNamingTheFileTheLayerAndTheField(string json, string expected)
    {
        var path = Path.Combine(folder, "job.json");
        File.WriteAllText(path, json);

        var ex = Assert.Throws<PlanException>(() => JobFile.Load(path));

        Assert.StartsWith(path, ex.Message, StringComparison.Ordinal);
        Assert.Contains(expected, ex.Message, StringComparison.Ordinal);
        Assert.DoesNotContain('\n', ex.Message);
    }

    [Fact]
    public void Prepare_RasterModeForADrawing_RefusedNamingTheLayer()
    {
        JobLayer[] layers = [new JobLayer { Name = "cut", Source = TestDrawings.File("layers.svg"), Mode = LayerMode.Raster }];

        var ex = Assert.Throws<PlanException>(() => LayeredJob.Prepare(layers, MachineProfile.Default));

        Assert.Contains("layer \"cut\"", ex.Message, StringComparison.Ordinal);
        Assert.Contains("is a drawing: its mode is outline, fill or both", ex.Message, StringComparison.Ordinal);
    }

    public void Dispose() => Directory.Delete(folder, recursive: true);
}
