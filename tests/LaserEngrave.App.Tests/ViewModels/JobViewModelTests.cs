using LaserEngrave.App.Services;
using LaserEngrave.App.ViewModels;
using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Imaging;
using LaserEngrave.Core.Jobs;
using NSubstitute.ExceptionExtensions;
using NSubstitute;

namespace LaserEngrave.App.Tests.ViewModels;

public sealed class JobViewModelTests
{
    private static JobViewModel Loaded(string asset = "qr-code.bmp")
    {
        var job = new JobViewModel(new ImageService(), MachineProfile.Default);
        Assert.True(job.LoadImage(TestFiles.Asset(asset)));
        return job;
    }

    [Fact]
    public void LoadImage_GoodFile_PlansWithEstimate()
    {
        var job = Loaded();

        Assert.NotNull(job.Job);
        Assert.Equal(41, job.ImageInfo!.Width);
        Assert.True(job.EstimatedSeconds > 0);
        Assert.Empty(job.Errors);
    }

    [Fact]
    public void LoadImage_Drawing_PlansItsStrokesWithEstimateAndNoMask()
    {
        var job = new JobViewModel(new ImageService(), MachineProfile.Default);
        job.OriginXMm = 5;
        job.OriginYMm = 5;
        job.WidthMm = 10;

        Assert.True(job.LoadImage(TestFiles.Asset(Path.Combine("drawings", "hexagons.dxf"))));

        Assert.True(job.IsDrawing);
        Assert.Null(job.Job);
        Assert.Null(job.Mask);
        var drawing = Assert.IsType<Core.Jobs.PreparedDrawing>(job.Drawing);
        Assert.Equal(10, drawing.Plan.WidthMm, 9);
        Assert.Equal(drawing.WholeRunSeconds(1), job.EstimatedSeconds!.Value, 9);
        Assert.Equal(Math.Round(drawing.Plan.HeightMm, 4), job.HeightMm);
        Assert.Empty(job.Errors);
    }

    [Fact]
    public void EditWidth_Drawing_ScalesItAndThePlanFollows()
    {
        var job = new JobViewModel(new ImageService(), MachineProfile.Default);
        job.OriginXMm = 5;
        job.OriginYMm = 5;
        job.WidthMm = 10;
        job.LoadImage(TestFiles.Asset(Path.Combine("drawings", "hexagons.dxf")));
        var before = job.Drawing!.Plan.BurnLengthMm;

        job.EditWidth(20);

        Assert.Equal(20, job.Drawing!.Plan.WidthMm, 9);
        Assert.InRange(job.Drawing.Plan.BurnLengthMm, before * 1.99, before * 2.01);
    }

    private static JobViewModel Drawing(string name)
    {
        var job = new JobViewModel(new ImageService(), MachineProfile.Default);
        job.OriginXMm = 5;
        job.OriginYMm = 5;
        job.WidthMm = 10;
        Assert.True(job.LoadImage(TestFiles.Asset(Path.Combine("drawings", name))));
        return job;
    }

    [Fact]
    public void DrawingFill_Both_PlansFillRowsAtThePitchAsTheCommandLineDoes()
    {
        var job = Drawing("hexagons.dxf");
        var outlines = job.Drawing!.Plan.Paths.Count;

        job.Batch(() =>
        {
            job.DrawingFill = Core.Vectors.VectorFillMode.Both;
            job.FillPitchUm = 200;
        });

        var plan = job.Drawing!.Plan;
        var same = Core.Vectors.VectorPlanner.Plan(job.ImagePath!, new Core.Vectors.VectorOptions { Fill = Core.Vectors.VectorFillMode.Both, FillPitchUm = 200, WidthMm = 10, Origin = new OriginMm(5, 5) }, MachineProfile.Default);
        Assert.NotEmpty(plan.FillRows);
        Assert.Equal(same.FillRows.Count, plan.FillRows.Count);
        Assert.True(plan.Paths.Count > outlines);
        Assert.Equal(same.BurnLengthMm, plan.BurnLengthMm, 9);
    }

    [Theory]
    [InlineData(JobViewModel.ToleranceField, 0.001, "chord tolerance 0.001 µm: must be between 0.01 and 1000 µm")]
    [InlineData(JobViewModel.FillPitchField, 0, "fill pitch 0 µm: must be between 0.1 and 10000 µm")]
    public void DrawingOption_OutOfRange_FieldSaysWhyAndNothingIsPlanned(string field, double value, string message)
    {
        var job = Drawing("hexagons.dxf");

        if (field == JobViewModel.ToleranceField)
        {
            job.ToleranceUm = value;
        }
        else
        {
            job.FillPitchUm = value;
        }

        Assert.Equal(message, job.Errors[field]);
        Assert.Null(job.Drawing);
        Assert.Null(job.EstimatedSeconds);
    }

    [Fact]
    public void ToleranceUm_Coarser_FewerVerticesAndTheSummaryFollows()
    {
        var job = Drawing("curves.dxf");
        var fine = job.Drawing!.Plan.Paths.Sum(p => p.Points.Count);

        job.ToleranceUm = 50;

        Assert.True(job.Drawing!.Plan.Paths.Sum(p => p.Points.Count) < fine);
        Assert.Empty(job.Errors);
    }

    [Fact]
    public void DrawingLayer_OneOfTheDrawingsLayers_BurnsOnlyItPlacedAsInTheWhole()
    {
        var job = Drawing("layers.svg");
        Assert.Equal(["cut", "mark"], job.DrawingLayers);
        var whole = job.Drawing!.Plan;

        job.DrawingLayer = "mark";

        var mark = job.Drawing!.Plan;
        Assert.True(mark.Paths.Count < whole.Paths.Count);
        Assert.True(mark.BurnLengthMm < whole.BurnLengthMm);
        Assert.Equal("mark", job.ToSettings().DrawingLayer);
    }

    [Fact]
    public void PathOrderSummary_Drawing_GivesBurnLengthAndTravelSavedAgainstDrawingOrder()
    {
        var job = Drawing("scattered.dxf");
        var plan = job.Drawing!.Plan;

        Assert.Contains(plan.TravelSavedPercent.ToString("0.#", System.Globalization.CultureInfo.InvariantCulture) + " % saved", job.PathOrderSummary, StringComparison.Ordinal);
        Assert.StartsWith("burn " + plan.BurnLengthMm.ToString("0.###", System.Globalization.CultureInfo.InvariantCulture) + " mm", job.PathOrderSummary, StringComparison.Ordinal);
        Assert.True(plan.TravelSavedPercent > 50);

        job.DrawingOrder = true;

        Assert.Equal(job.Drawing!.Plan.TravelDrawingOrderMm, job.Drawing.Plan.TravelMm, 6);
    }

    [Fact]
    public void LoadImage_ImageAfterDrawing_DrawingLayersGo()
    {
        var job = Drawing("layers.svg");

        Assert.True(job.LoadImage(TestFiles.Asset("qr-code.bmp")));

        Assert.Empty(job.DrawingLayers);
        Assert.Null(job.PathOrderSummary);
    }

    [Fact]
    public void LoadImage_BadDrawingAfterGoodImage_KeepsTheImageAndSaysWhy()
    {
        var job = Loaded();
        using var folder = TestFiles.NewFolder();
        var bad = Path.Combine(folder.Path, "bad.dxf");
        File.WriteAllText(bad, "0\nSECTION\n2\nENTITIES\n0\nLINE\n5\n2A\n10\n1,5\n");

        Assert.False(job.LoadImage(bad));

        Assert.EndsWith("qr-code.bmp", job.ImagePath, StringComparison.Ordinal);
        Assert.NotNull(job.Job);
        Assert.Contains("bad.dxf: LINE (handle 2A, line 6)", job.Errors[JobViewModel.ImageField], StringComparison.Ordinal);
    }

    [Fact]
    public void LoadImage_BadImage_ErrorBesideImageAndNoPlan()
    {
        var images = Substitute.For<IImageService>();
        images.Load("broken.png").Throws(new ImageLoadException("broken.png", "the PNG signature is missing"));
        var job = new JobViewModel(images, MachineProfile.Default);

        var loaded = job.LoadImage("broken.png");

        Assert.False(loaded);
        Assert.Null(job.Job);
        Assert.Equal("broken.png: the PNG signature is missing", job.Errors[JobViewModel.ImageField]);
    }

    [Fact]
    public void LoadImage_BadImageAfterGoodOne_KeepsGoodImage()
    {
        var job = Loaded();
        using var folder = TestFiles.NewFolder();
        var bad = Path.Combine(folder.Path, "bad.png");
        File.WriteAllText(bad, "not an image");

        Assert.False(job.LoadImage(bad));

        Assert.EndsWith("qr-code.bmp", job.ImagePath, StringComparison.Ordinal);
        Assert.Contains("bad.png", job.Errors[JobViewModel.ImageField], StringComparison.Ordinal);
    }

    [Fact]
    public void EditWidth_AspectLocked_HeightFollowsAndEstimateChanges()
    {
        var job = Loaded();
        var before = job.EstimatedSeconds;

        job.EditWidth(10);

        Assert.Equal(10, job.HeightMm, 3);
        Assert.Equal(10_000.0 / 41, job.PitchUm, 3);
        Assert.NotEqual(before, job.EstimatedSeconds);
    }

    [Fact]
    public void EditHeight_AspectUnlockedWrongAspect_ErrorBesideWidth()
    {
        var job = Loaded();
        job.AspectLocked = false;

        job.EditHeight(9);

        Assert.Null(job.Job);
        Assert.Contains("aspect", job.Errors[JobViewModel.WidthField], StringComparison.OrdinalIgnoreCase);
    }

    [Fact]
    public void EditPitch_Microsteps_SizeFollowsPitch()
    {
        var job = Loaded();

        job.EditMicrostepsPerPixel(100);

        Assert.Equal(SizeMode.Pitch, job.SizeMode);
        Assert.Equal(100, job.MicrostepsPerPixel, 9);
        Assert.Equal(41 * 100 * MachineProfile.Default.X.MicrostepUm / 1000, job.WidthMm, 3);
    }

    [Fact]
    public void OriginX_JobOutsideTravel_RefusedBesideOriginWithTheRulesSentence()
    {
        // Issue 35: a typed origin was only warned of while the same place dropped on the stage was refused.
        var job = Loaded();

        job.OriginXMm = 58;

        Assert.NotNull(job.Job);
        Assert.False(job.Job!.Geometry.FitsTravel);
        Assert.Equal(JobRules.Placement(job.Job), job.Errors[JobViewModel.OriginField]);
        Assert.False(job.Warnings.ContainsKey(JobViewModel.OriginField));
        Assert.Equal(job.Errors[JobViewModel.OriginField], job.Engraving!.StartProblem);
    }

    [Fact]
    public void PlaceAt_OffTheTravel_RefusedWithTheTypedOriginsSentenceOriginKept()
    {
        var job = Loaded();
        job.OriginXMm = 1;

        var refused = job.PlaceAt(58, 1);
        var placed = job.PlaceAt(20.123, 7.456);

        Assert.Equal("not placed at 58, 1 mm: " + JobRules.Placement(PreparedJob.Prepare(job.Job!.Spec with { Origin = new OriginMm(58, 1) })), refused);
        Assert.Null(placed);
        Assert.Equal((20.12, 7.46), (job.OriginXMm, job.OriginYMm));
        Assert.Empty(job.Errors);
    }

    [Fact]
    public void PulseEnergy_BelowZero_RefusedBesideItsFieldAsTheCommandLineRefusesIt()
    {
        // Issue 35: the app once dropped a pulse energy of 0 or below without a word; the command line refused it.
        var job = Loaded();

        job.PulseEnergyUj = -5;

        Assert.Equal("pulse energy -5 µJ: must be a finite number above 0 (or left out: not known)", job.Errors[JobViewModel.PulseEnergyField]);
        job.PulseEnergyUj = null;
        Assert.Empty(job.Errors);
        Assert.Null(job.ToSettings().PulseEnergyUj);
    }

    [Fact]
    public void EditPitch_BelowSpot_WarningBesidePitch()
    {
        var job = Loaded();

        job.EditPitch(5);

        Assert.True(job.Warnings.ContainsKey(JobViewModel.PitchField));
    }

    [Theory]
    [InlineData(nameof(JobViewModel.BurnSpeedMmPerS), JobViewModel.BurnSpeedField)]
    [InlineData(nameof(JobViewModel.TravelSpeedMmPerS), JobViewModel.TravelSpeedField)]
    [InlineData(nameof(JobViewModel.AccelerationMmPerS2), JobViewModel.AccelerationField)]
    [InlineData(nameof(JobViewModel.LaserFrequencyHz), JobViewModel.FrequencyField)]
    public void ProcessValue_Zero_ErrorBesideItAndNoPlan(string property, string field)
    {
        var job = Loaded();

        typeof(JobViewModel).GetProperty(property)!.SetValue(job, 0.0);

        Assert.Null(job.Job);
        Assert.Null(job.EstimatedSeconds);
        Assert.Contains("0", job.Errors[field], StringComparison.Ordinal);
    }

    [Fact]
    public void BurnSpeed_Higher_EstimateShorter()
    {
        var job = Loaded();
        var slow = job.EstimatedSeconds!.Value;

        job.BurnSpeedMmPerS = 3;

        Assert.True(job.EstimatedSeconds < slow);
    }

    [Fact]
    public void Passes_Two_EstimateAddsAPassWithoutHoming()
    {
        var job = Loaded();
        var one = job.EstimatedSeconds!.Value;
        var statistics = job.Job!.Statistics;

        job.Passes = 2;

        Assert.Equal(one, statistics.PreparationSeconds + statistics.EngravingSeconds, 6);
        Assert.Equal(one + statistics.EngravingSeconds + statistics.PassSetupSeconds, job.EstimatedSeconds!.Value, 6);
        Assert.True(statistics.PassSetupSeconds < statistics.PreparationSeconds, "a later pass does not home");
    }

    [Fact]
    public void Threshold_Changed_MaskRebuilt()
    {
        var job = Loaded("text-banner.png");
        var version = job.MaskVersion;

        job.ThresholdPercent = 1;

        Assert.Equal(version + 1, job.MaskVersion);
    }

    [Fact]
    public void Invert_Toggled_BurnsTheOtherPixels()
    {
        var job = Loaded();
        var black = job.Mask!.CountSet();

        job.Invert = true;

        Assert.Equal((41L * 41) - black, job.Mask!.CountSet());
    }

    [Fact]
    public void Apply_Settings_RoundTripsThroughToSettings()
    {
        var job = Loaded();
        var settings = job.ToSettings() with { WidthMm = 7, OriginXMm = 3, Passes = 3, OverscanMm = 0.5, Dither = DitherMethod.Atkinson };

        job.Apply(settings);

        Assert.Equal(settings with { HeightMm = job.HeightMm, PitchUm = job.PitchUm }, job.ToSettings());
        Assert.Equal(7, job.HeightMm, 3);
    }

    /// <summary>The real image service, keeping only a weak reference to each decoded image so a test can see it freed.</summary>
    private sealed class WatchedImages : IImageService
    {
        private readonly ImageService _real = new();

        public List<WeakReference> Decoded { get; } = [];

        public LoadedImage Load(string path)
        {
            var image = _real.Load(path);
            Decoded.Add(new WeakReference(image));
            return image;
        }

        public BitMask BuildMask(LoadedImage image, MaskOptions options) => _real.BuildMask(image, options);

        public Core.Jobs.PreparedJob Prepare(Core.Jobs.JobSpec spec, ImageInfo info, BitMask mask) => _real.Prepare(spec, info, mask);

        public byte[] RenderOriginalPng(LoadedImage image, int maxSidePx) => _real.RenderOriginalPng(image, maxSidePx);

        public byte[] RenderMaskPng(BitMask mask, int maxSidePx) => _real.RenderMaskPng(mask, maxSidePx);
    }

    [Fact]
    public void LoadImage_LargeImage_OnlyTheMaskAndPreviewKeptAndThresholdDecodesAgain()
    {
        using var folder = TestFiles.NewFolder();
        var path = Path.Combine(folder.Path, "large.png");
        const int side = 3000; // RGBA: 36 MB decoded, above what the view-model keeps
        using (var file = File.Create(path))
        {
            PngWriter.WriteRgba(file, side, side, new byte[side * side * 4]);
        }

        var images = new WatchedImages();
        var job = new JobViewModel(images, MachineProfile.Default);

        Assert.True(job.LoadImage(path));
        GC.Collect();
        GC.WaitForPendingFinalizers();

        Assert.False(Assert.Single(images.Decoded).IsAlive);
        Assert.Null(job.Image);
        Assert.NotNull(job.OriginalPreviewPng());
        Assert.Equal(side, job.Mask!.Width);
        var version = job.MaskVersion;
        job.Invert = true;
        Assert.Equal(2, images.Decoded.Count);
        Assert.Equal(version + 1, job.MaskVersion);
        Assert.Equal(0, job.Mask.CountSet());
    }

    [Fact]
    public void LoadImage_SmallImage_KeptForTheNextThreshold()
    {
        var images = new WatchedImages();
        var job = new JobViewModel(images, MachineProfile.Default);
        job.LoadImage(TestFiles.Asset("qr-code.bmp"));

        job.ThresholdPercent = 20;

        Assert.Single(images.Decoded);
        Assert.NotNull(job.Image);
    }

    /// <summary>A stage whose Y axis is slower and gentler than X, on a gate that takes at most 500 Hz.</summary>
    private static readonly MachineProfile SlowY = new()
    {
        Y = new AxisProfile { DeviceNumber = 2, MaxSpeedMmPerS = 2, MaxAccelerationMmPerS2 = 100 },
        Gate = new LaserGateProfile { MaxFrequencyHz = 500 },
        LaserFrequencyHz = 400,
        TravelSpeedMmPerS = 2,
    };

    [Theory]
    [InlineData(nameof(JobViewModel.BurnSpeedMmPerS), 3, JobViewModel.BurnSpeedField)]
    [InlineData(nameof(JobViewModel.BurnSpeedMmPerS), 1e-9, JobViewModel.BurnSpeedField)]
    [InlineData(nameof(JobViewModel.LaserFrequencyHz), 1000, JobViewModel.FrequencyField)]
    [InlineData(nameof(JobViewModel.AccelerationMmPerS2), 150, JobViewModel.AccelerationField)]
    [InlineData(nameof(JobViewModel.OverscanMm), 100, JobViewModel.OverscanField)]
    [InlineData(nameof(JobViewModel.PitchUm), 0.05, JobViewModel.PitchField)]
    public void Field_ValueTheCommandLineRefuses_RefusedBesideItNow(string property, double value, string field)
    {
        // Each once passed the app's own checks (X's speed alone, a fixed 100 kHz, any overscan or pitch above 0) while the command line refused it.
        var job = new JobViewModel(new ImageService(), SlowY);
        Assert.True(job.LoadImage(TestFiles.Asset("qr-code.bmp")));
        Assert.Empty(job.Errors);

        if (property == nameof(JobViewModel.PitchUm))
        {
            job.EditPitch(value);
        }
        else
        {
            typeof(JobViewModel).GetProperty(property)!.SetValue(job, value);
        }

        Assert.Equal(JobRules.Check(job.ToSettings(), MachineLimits.Of(SlowY)).Single().Message, job.Errors[field]);
        Assert.Null(job.Job);
    }

    /// <summary>The default machine with a frequency-only gate: the host times every switching, so its lateness limits the speed.</summary>
    internal static readonly MachineProfile FrequencyOnly = MachineProfile.Default with
    {
        Gate = new LaserGateProfile { Kind = LaserGateKind.FrequencyOnly, WatchdogMs = 0 },
    };

    [Fact]
    public void BurnSpeed_BeyondWhatThisComputerHoldsOnAFrequencyOnlyGate_TheSentenceUnderTheSpeedField()
    {
        // Issue 34: 1.5 µm of tolerance over a lab PC's 0.5 ms is 3 mm/s; said under the field, Start disabled.
        var job = new JobViewModel(new ImageService(), FrequencyOnly);
        Assert.True(job.LoadImage(TestFiles.Asset("qr-code.bmp")));

        job.BurnSpeedMmPerS = 3.5;

        Assert.Equal(
            "burn speed 3.5 mm/s: faster than this computer can hold with this gate: it wakes up to 0.5 ms late (the profile's latency.hostLatenessMs), 1.75 µm at 3.5 mm/s, past the edge tolerance of 1.5 µm; the fastest it holds is 3 mm/s (a gate that times its switch-ons, CAPS? listing AFTER, holds any)",
            job.Errors[JobViewModel.BurnSpeedField]);

        job.BurnSpeedMmPerS = 3;
        Assert.False(job.Errors.ContainsKey(JobViewModel.BurnSpeedField));
    }

    [Fact]
    public void Pitch_AboveAMillimetre_PlannedAsTheCommandLineDoes()
    {
        // The app once refused a pitch above 1000 µm that the command line and the run logs took.
        var job = Loaded();

        job.EditPitch(1400);

        Assert.Empty(job.Errors);
        Assert.NotNull(job.Job);
    }

    [Fact]
    public void Width_GivingPixelsBelowAMicrostep_RefusedAsTheCommandLineRefusesIt()
    {
        // Once only a warning here, while the command line refused the same size before planning.
        var job = Loaded();

        job.EditWidth(0.001);

        Assert.Equal("width 0.001 mm: gives pixels of 0.02439 µm, below one microstep (0.09922 µm), the smallest step the stage makes; make the job larger", job.Errors[JobViewModel.WidthField]);
        Assert.DoesNotContain("microstep", job.Warnings.GetValueOrDefault(JobViewModel.PitchField) ?? string.Empty, StringComparison.Ordinal);
    }
}
