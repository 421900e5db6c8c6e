using LaserEngrave.App.Services;
using LaserEngrave.App.ViewModels;
using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Jobs;
using LaserEngrave.Core.Planning;
using LaserEngrave.Core.Vectors;
using NSubstitute;
using NSubstitute.ExceptionExtensions;

namespace LaserEngrave.App.Tests.ViewModels;

/// <summary>The Layers view: building a job of layers from the open job, editing, ordering, opening and saving job files.</summary>
public sealed class LayersViewModelTests : IDisposable
{
    private readonly TestFiles.TempFolder _folder = TestFiles.NewFolder();
    private readonly IJobFiles _files = Substitute.For<IJobFiles>();
    private readonly MachineActivity _activity = new();
    private readonly JobViewModel _job;
    private readonly LayersViewModel _layers;

    public LayersViewModelTests()
    {
        // The plan is Core's own (as engrave --job makes it); only the files are faked.
        _files.Prepare(Arg.Any<IReadOnlyList<JobLayer>>(), Arg.Any<MachineProfile>()).Returns(c => LayeredJob.Prepare(c.Arg<IReadOnlyList<JobLayer>>(), c.Arg<MachineProfile>()));
        _files.DefaultFolder.Returns(_folder.Path);
        _job = new JobViewModel(new ImageService(), MachineProfile.Default, _activity);
        _layers = new LayersViewModel(_files, _job, _activity);
    }

    private static string Plate => TestFiles.Asset(Path.Combine("jobs", "plate.json"));

    public void Dispose() => _folder.Dispose();

    private void OpenDrawing(string layer)
    {
        _job.Batch(() =>
        {
            _job.OriginXMm = 10;
            _job.OriginYMm = 10;
            _job.DrawingLayer = null;
        });
        Assert.True(_job.LoadImage(TestFiles.Asset(Path.Combine("drawings", "layers.svg"))));
        _job.DrawingLayer = layer;
    }

    [Fact]
    public void AddCurrent_DrawingLayerThenImage_TwoLayersWithTheFieldsValuesPlannedAsTheCommandLineDoes()
    {
        OpenDrawing("mark");
        _job.Batch(() =>
        {
            _job.DrawingFill = VectorFillMode.Both;
            _job.FillPitchUm = 100;
            _job.BurnSpeedMmPerS = 0.5;
        });
        Assert.True(_layers.AddCurrent());
        Assert.True(_job.LoadImage(TestFiles.Asset("qr-code.bmp")));
        _job.Batch(() =>
        {
            _job.EditWidth(3);
            _job.OriginXMm = 24;
            _job.OriginYMm = 22;
            _job.Passes = 2;
            _job.ThresholdPercent = 30;
            _job.Invert = true;
        });

        Assert.True(_layers.AddCurrent());

        Assert.Equal(["layers mark", "qr-code"], _layers.Layers.Select(l => l.Name));
        var mark = _layers.Layers[0];
        Assert.Equal((LayerMode.Both, "mark", 100.0, 0.5), (mark.Mode, mark.DrawingLayer, mark.FillPitchUm!.Value, mark.SpeedMmPerS!.Value));
        Assert.Equal((LayerMode.Raster, 3.0, 2), (_layers.Layers[1].Mode, _layers.Layers[1].WidthMm!.Value, _layers.Layers[1].Passes));
        Assert.Equal(new Core.Imaging.MaskOptions { ThresholdPercent = 30, Invert = true }, _layers.Layers[1].Mask);
        Assert.True(((ImagePart)_layers.Job!.Layers[1]).Image.Mask.ContentEquals(_job.Mask!));
        Assert.Equal(Core.Imaging.MaskOptions.Default, mark.Mask);
        var same = LayeredJob.Prepare(_layers.Layers, MachineProfile.Default);
        Assert.Equal(same.EstimatedSeconds, _layers.EstimatedSeconds!.Value, 9);
        Assert.NotEmpty(((DrawingPart)_layers.Job!.Layers[0]).Drawing.Plan.FillRows);
        Assert.Null(_layers.Error);
        Assert.True(_layers.IsActive);
    }

    [Fact]
    public void AddCurrent_NothingOpen_SaysWhyAndAddsNothing()
    {
        Assert.False(_layers.AddCurrent());

        Assert.Contains("open an image or drawing first", _layers.FileError, StringComparison.Ordinal);
        Assert.Empty(_layers.Layers);
    }

    [Fact]
    public void MoveRemoveAndRename_ChangeTheOrderAndThePlanFollows()
    {
        _files.Load(Plate).Returns(JobFile.Load(Plate));
        Assert.True(_layers.Open(Plate));
        var version = _layers.PlanVersion;

        _layers.Move(2, -1);
        _layers.Move(0, -1);
        _layers.Update(0, _layers.Layers[0] with { Name = "first marks" });
        _layers.Remove(1);

        Assert.Equal(["first marks", "logo"], _layers.Layers.Select(l => l.Name));
        Assert.Equal(["first marks", "logo"], _layers.Job!.Layers.Select(l => l.Layer.Name));
        Assert.True(_layers.PlanVersion > version);
    }

    [Fact]
    public void Update_PassesOutOfRange_ErrorNamesTheLayerAndNothingIsPlanned()
    {
        _files.Load(Plate).Returns(JobFile.Load(Plate));
        _layers.Open(Plate);

        _layers.Update(1, _layers.Layers[1] with { Passes = 0 });

        Assert.Equal("layer \"logo\": passes 0: must be 1..100 (burns of the plan over the same place)", _layers.Error);
        Assert.Equal(1, _layers.ErrorLayer);
        Assert.Null(_layers.Job);
        Assert.Null(_layers.EstimatedSeconds);
    }

    [Fact]
    public void Update_SpeedAboveTheStages_ErrorNamesTheLayer()
    {
        _files.Load(Plate).Returns(JobFile.Load(Plate));
        _layers.Open(Plate);

        _layers.Update(0, _layers.Layers[0] with { SpeedMmPerS = 1e6 });

        Assert.StartsWith("layer \"marks\": ", _layers.Error, StringComparison.Ordinal);
        Assert.Null(_layers.Job);
    }

    [Fact]
    public void Open_BadJobFile_SaysWhyAndKeepsTheLayers()
    {
        _files.Load(Plate).Returns(JobFile.Load(Plate));
        _layers.Open(Plate);
        _files.Load("bad.json").Throws(new PlanException("bad.json: layer 1 \"x\": passes 0.5 must be a whole number 1..100"));

        Assert.False(_layers.Open("bad.json"));

        Assert.Equal("bad.json: layer 1 \"x\": passes 0.5 must be a whole number 1..100", _layers.FileError);
        Assert.Equal(3, _layers.Layers.Count);
    }

    [Fact]
    public void Save_Layers_WritesThemThroughTheJobFilesAtThePathGiven()
    {
        _files.Load(Plate).Returns(JobFile.Load(Plate));
        _layers.Open(Plate);
        var path = Path.Combine(_folder.Path, "copy.json");

        Assert.True(_layers.Save(path));

        _files.Received(1).Save(path, Arg.Is<IReadOnlyList<JobLayer>>(l => l.SequenceEqual(_layers.Layers)));
        Assert.Equal(path, _layers.JobPath);
        Assert.Equal(path, _layers.SuggestedPath);
    }

    [Fact]
    public void Save_RealFiles_TheCommandLineReaderReadsTheSameLayers()
    {
        var files = new JobFiles(new AppFolders(_folder.Path));
        var layers = new LayersViewModel(files, _job, _activity);
        OpenDrawing("cut");
        layers.AddCurrent();
        layers.Update(0, layers.Layers[0] with { Passes = 3, Mode = LayerMode.Fill });
        var path = Path.Combine(files.DefaultFolder, "sub", "cut.json");

        Assert.True(layers.Save(path));

        Assert.Equal(layers.Layers, JobFile.Load(path));
    }

    [Fact]
    public void Save_SingleImageNoLayers_OneLayerFileOpenedBackAsTheSameSingleJob()
    {
        var files = new JobFiles(new AppFolders(_folder.Path));
        var layers = new LayersViewModel(files, _job, _activity);
        Assert.True(_job.LoadImage(TestFiles.Asset("qr-code.bmp")));
        _job.Batch(() =>
        {
            _job.EditWidth(7);
            _job.OriginXMm = 3;
            _job.OriginYMm = 4;
            _job.BurnSpeedMmPerS = 0.5;
            _job.LaserFrequencyHz = 2000;
            _job.Passes = 2;
            _job.Dither = Core.Imaging.DitherMethod.Atkinson;
        });
        var saved = _job.ToSettings();
        var mask = _job.Mask!.CountSet();
        var path = Path.Combine(files.DefaultFolder, "qr.json");

        Assert.True(layers.Save(path), layers.FileError);

        Assert.Single(JobFile.Load(path));
        Assert.Empty(layers.Layers);
        Assert.True(_job.LoadImage(TestFiles.Asset("text-banner.png")));
        _job.Batch(() =>
        {
            _job.EditWidth(5);
            _job.BurnSpeedMmPerS = 1;
            _job.Dither = Core.Imaging.DitherMethod.None;
        });

        Assert.True(layers.Open(path), layers.FileError);

        Assert.Empty(layers.Layers);
        Assert.Equal(saved, _job.ToSettings());
        Assert.Equal(mask, _job.Mask!.CountSet());
        Assert.NotNull(_job.Engraving);
        Assert.Equal(Path.GetFullPath(path), layers.JobPath);
    }

    [Fact]
    public void Save_SingleDrawingLayer_OpenedBackWithItsLayerFillAndPlan()
    {
        var files = new JobFiles(new AppFolders(_folder.Path));
        var layers = new LayersViewModel(files, _job, _activity);
        OpenDrawing("cut");
        _job.Batch(() =>
        {
            _job.DrawingFill = VectorFillMode.Fill;
            _job.FillPitchUm = 80;
            _job.Passes = 3;
        });
        var strokes = _job.Drawing!.Schedule.Strokes.Count;
        var estimate = _job.EstimatedSeconds;
        var path = Path.Combine(files.DefaultFolder, "cut.json");
        Assert.True(layers.Save(path), layers.FileError);
        Assert.True(_job.LoadImage(TestFiles.Asset("qr-code.bmp")));

        Assert.True(layers.Open(path), layers.FileError);

        Assert.Empty(layers.Layers);
        Assert.Equal("cut", _job.DrawingLayer);
        Assert.Equal(VectorFillMode.Fill, _job.DrawingFill);
        Assert.Equal(80, _job.FillPitchUm);
        Assert.Equal(3, _job.Passes);
        Assert.Equal(strokes, _job.Drawing!.Schedule.Strokes.Count);
        Assert.Equal(estimate, _job.EstimatedSeconds);
    }

    [Fact]
    public void AddArray_TwoRowsThreeColumns_SixLayersAtTheirOriginsPlannedAlike()
    {
        Assert.True(_job.LoadImage(TestFiles.Asset("qr-code.bmp")));
        _job.Batch(() =>
        {
            _job.EditWidth(4);
            _job.OriginXMm = 2;
            _job.OriginYMm = 3;
        });
        _layers.ArrayRows = 2;
        _layers.ArrayColumns = 3;
        _layers.ArrayPitchXMm = 5;
        _layers.ArrayPitchYMm = 6;

        Assert.True(_layers.AddArray(), _layers.FileError);

        Assert.Equal(6, _layers.Layers.Count);
        Assert.Equal(
            [new OriginMm(2, 3), new OriginMm(7, 3), new OriginMm(12, 3), new OriginMm(2, 9), new OriginMm(7, 9), new OriginMm(12, 9)],
            _layers.Layers.Select(l => l.Origin));
        Assert.Equal("qr-code r2c3", _layers.Layers[5].Name);
        Assert.Null(_layers.Error);
        var job = _layers.Job!;
        Assert.All(job.Layers, l => Assert.True(((ImagePart)l).Image.Mask.ContentEquals(_job.Mask!)));
        Assert.All(job.Layers, l => Assert.Equal(4, l.SizeMm.WidthMm, 3));
    }

    [Fact]
    public void AddArray_OneByOne_RefusedSayingWhy()
    {
        Assert.True(_job.LoadImage(TestFiles.Asset("qr-code.bmp")));
        _layers.ArrayRows = 1;
        _layers.ArrayColumns = 1;

        Assert.False(_layers.AddArray());

        Assert.StartsWith("an array of 1 × 1: give at least 2 copies", _layers.FileError, StringComparison.Ordinal);
        Assert.Empty(_layers.Layers);
    }

    [Fact]
    public void Save_NothingOpenNoLayers_RefusedSayingWhy()
    {
        Assert.False(_layers.CanSave);

        Assert.False(_layers.Save(Path.Combine(_folder.Path, "job.json")));

        Assert.Equal("open an image or drawing first: there is no job to save", _layers.FileError);
        _files.DidNotReceive().Save(Arg.Any<string>(), Arg.Any<IReadOnlyList<JobLayer>>());
    }

    [Fact]
    public void Save_SingleImageBurningDots_RefusedNotWrittenAsARaster()
    {
        Assert.True(_job.LoadImage(TestFiles.Asset("qr-code.bmp")));
        _job.Mode = PlanMode.Dots;

        Assert.False(_layers.Save(Path.Combine(_folder.Path, "dots.json")));

        Assert.Contains("burns dots", _layers.FileError, StringComparison.Ordinal);
        _files.DidNotReceive().Save(Arg.Any<string>(), Arg.Any<IReadOnlyList<JobLayer>>());
    }

    [Fact]
    public void ToDownload_SingleImage_FullPathSourcesThatOpenFromAnotherFolder()
    {
        var files = new JobFiles(new AppFolders(_folder.Path));
        var layers = new LayersViewModel(files, _job, _activity);
        Assert.True(_job.LoadImage(TestFiles.Asset("qr-code.bmp")));
        Assert.True(layers.CanSave);
        Assert.Equal("qr-code.json", layers.DownloadName);

        var bytes = layers.ToDownload();

        Assert.NotNull(bytes);
        var elsewhere = Path.Combine(_folder.Path, "uploads", "0123456789abcdef", "qr-code.json");
        Directory.CreateDirectory(Path.GetDirectoryName(elsewhere)!);
        File.WriteAllBytes(elsewhere, bytes);
        var layer = Assert.Single(JobFile.Load(elsewhere));
        Assert.Equal(Path.GetFullPath(TestFiles.Asset("qr-code.bmp")), layer.Source);
        Assert.True(layers.Open(elsewhere), layers.FileError);
        Assert.Equal(Path.GetFullPath(TestFiles.Asset("qr-code.bmp")), Path.GetFullPath(_job.ImagePath!));
    }

    [Fact]
    public void UnchangedJobFile_OpenedThenEdited_NamedUntilALayerChanges()
    {
        _files.Load(Plate).Returns(JobFile.Load(Plate));
        _layers.Open(Plate);

        Assert.Equal(Path.GetFullPath(Plate), _layers.UnchangedJobFile);

        _layers.Update(0, _layers.Layers[0] with { Passes = 2 });

        Assert.Null(_layers.UnchangedJobFile);
        var path = Path.Combine(_folder.Path, "edited.json");
        _layers.Save(path);
        Assert.Equal(path, _layers.UnchangedJobFile);
    }

    [Fact]
    public void Save_NotJson_RefusedWithoutWriting()
    {
        _files.Load(Plate).Returns(JobFile.Load(Plate));
        _layers.Open(Plate);

        Assert.False(_layers.Save(Path.Combine(_folder.Path, "job.txt")));

        Assert.Contains("a job file ends in .json", _layers.FileError, StringComparison.Ordinal);
        _files.DidNotReceive().Save(Arg.Any<string>(), Arg.Any<IReadOnlyList<JobLayer>>());
    }

    [Fact]
    public void Update_WhileARunHoldsTheMachine_RefusedAndUnchanged()
    {
        _files.Load(Plate).Returns(JobFile.Load(Plate));
        _layers.Open(Plate);
        Assert.True(_activity.TryBegin(MachineOperation.Run, out var lease, out _));
        using (lease)
        {
            Assert.Throws<MachineBusyException>(() => _layers.Update(0, _layers.Layers[0] with { Passes = 5 }));
            Assert.Throws<MachineBusyException>(() => _layers.Remove(0));
        }

        Assert.Equal(1, _layers.Layers[0].Passes);
        Assert.Equal(3, _layers.Layers.Count);
    }
}
