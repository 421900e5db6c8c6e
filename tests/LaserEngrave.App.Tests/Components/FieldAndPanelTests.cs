using Bunit;
using LaserEngrave.App.Components.Workspace;
using LaserEngrave.App.Services;
using LaserEngrave.App.ViewModels;
using LaserEngrave.Core.Geometry;
using NSubstitute;

namespace LaserEngrave.App.Tests.Components;

public sealed class NumberFieldTests : ComponentTest
{
    [Fact]
    public void Change_Number_CommittedWithItsValue()
    {
        double? committed = null;
        var cut = Render<NumberField>(p => p.Add(c => c.Id, "w").Add(c => c.Label, "Width").Add(c => c.Unit, "mm").Add(c => c.OnCommit, v => committed = v));

        cut.Find("input").Change("12.5");

        Assert.Equal(12.5, committed);
        Assert.Contains("mm", cut.Find(".unit").TextContent, StringComparison.Ordinal);
    }

    [Theory]
    [InlineData("5,5", 5.5)]
    [InlineData("0,5", 0.5)]
    [InlineData("5.5", 5.5)]
    public void Change_DecimalCommaOrPoint_CommittedAsTheCommandLineReadsIt(string typed, double expected)
    {
        double? committed = null;
        var cut = Render<NumberField>(p => p.Add(c => c.Id, "w").Add(c => c.Label, "Width").Add(c => c.OnCommit, v => committed = v));

        cut.Find("input").Change(typed);

        Assert.Equal(expected, committed);
        Assert.Equal("text", cut.Find("input").GetAttribute("type"));
    }

    [Fact]
    public void Change_DecimalComma_ShownWithTheCommaHereAndInEveryField()
    {
        double value = 10;
        var cut = Render<NumberField>(p => p.Add(c => c.Id, "w").Add(c => c.Label, "Width").Add(c => c.Value, value).Add(c => c.OnCommit, v => value = v));

        cut.Find("input").Change("20,5");
        var other = Render<NumberField>(p => p.Add(c => c.Id, "h").Add(c => c.Label, "Height").Add(c => c.Value, 1.25));
        var same = Render<NumberField>(p => p.Add(c => c.Id, "w2").Add(c => c.Label, "Width").Add(c => c.Value, value));

        Assert.Equal("20,5", same.Find("input").GetAttribute("value"));
        Assert.Equal("1,25", other.Find("input").GetAttribute("value"));
        Settings.Received().Save(Arg.Is<AppSettings>(s => s.DecimalComma));
    }

    [Fact]
    public void Change_DecimalPointAfterComma_PointShownAgain()
    {
        var cut = Render<NumberField>(p => p.Add(c => c.Id, "w").Add(c => c.Label, "Width").Add(c => c.OnCommit, _ => { }));
        cut.Find("input").Change("2,5");

        cut.Find("input").Change("3.5");
        var other = Render<NumberField>(p => p.Add(c => c.Id, "h").Add(c => c.Label, "Height").Add(c => c.Value, 1.25));

        Assert.Equal("1.25", other.Find("input").GetAttribute("value"));
        Assert.False(Main.Settings.DecimalComma);
    }

    [Theory]
    [InlineData("1.000,5", "more than one decimal mark")]
    [InlineData("1,000", "could be 1 or 1000: write 1000 or 1.0")]
    public void Change_ThousandsSeparator_NeverRead(string typed, string? problem)
    {
        double? committed = null;
        var cut = Render<NumberField>(p => p.Add(c => c.Id, "w").Add(c => c.Label, "Width").Add(c => c.OnCommit, v => committed = v));

        cut.Find("input").Change(typed);

        if (problem is null)
        {
            Assert.Equal(1.0, committed);
        }
        else
        {
            Assert.Null(committed);
            Assert.Contains(problem, cut.Find("[data-error=w]").TextContent, StringComparison.Ordinal);
        }
    }

    [Fact]
    public void Change_NotANumber_MessageBesideAndNothingCommitted()
    {
        var commits = 0;
        var cut = Render<NumberField>(p => p.Add(c => c.Id, "w").Add(c => c.Label, "Width").Add(c => c.OnCommit, _ => commits++));

        cut.Find("input").Change("12,5 mm");

        Assert.Equal(0, commits);
        Assert.Contains("is not a number", cut.Find("[data-error=w]").TextContent, StringComparison.Ordinal);
        Assert.Equal("true", cut.Find("input").GetAttribute("aria-invalid"));
    }
}

public sealed class ImagePanelTests : ComponentTest
{
    [Fact]
    public void NoImage_HintAndSamplesOffered()
    {
        var cut = Render<ImagePanel>(p => p.Add(c => c.Job, Main.Job).Add(c => c.Samples, Main.SampleImages));

        Assert.NotNull(cut.Find("#no-image"));
        Assert.Equal(2, cut.FindAll("#samples button").Count);
    }

    [Fact]
    public void ScanOffsetTestClicked_AsksForThePatternAndShowsItsError()
    {
        var asked = 0;
        var cut = Render<ImagePanel>(p => p.Add(c => c.Job, Main.Job).Add(c => c.Samples, Main.SampleImages)
            .Add(c => c.OnScanOffsetPattern, () => asked++).Add(c => c.PatternError, "the scan offset pattern could not be written: disk full"));

        cut.Find("#scan-offset-pattern").Click();

        Assert.Equal(1, asked);
        Assert.Equal("the scan offset pattern could not be written: disk full", cut.Find("#pattern-error").TextContent);
    }

    [Fact]
    public void SampleClicked_ImageOpenAndMaskCounted()
    {
        var cut = Render<ImagePanel>(p => p.Add(c => c.Job, Main.Job).Add(c => c.Samples, Main.SampleImages));

        cut.Find("#samples button[data-path$='qr-code.bmp']").Click();

        // The image is read, masked and planned off the page's path: its name and its mask's count show when it is ready.
        cut.WaitForAssertion(() =>
        {
            Assert.Contains("41 × 41 px", cut.Find("#image-meta").TextContent, StringComparison.Ordinal);
            Assert.Equal("563", cut.Find("#burn-pixels").TextContent);
        });
    }

    [Fact]
    public void Drawing_ModeToleranceLayerAndPathOrderShown_BadToleranceSaysWhy()
    {
        Assert.True(Main.Job.LoadImage(TestFiles.Asset(System.IO.Path.Combine("drawings", "layers.svg"))));
        var cut = Render<ImagePanel>(p => p.Add(c => c.Job, Main.Job));

        cut.Find("#drawingFill").Change(nameof(Core.Vectors.VectorFillMode.Both));
        cut.Find("#drawingLayer").Change("cut");

        Assert.Equal(Core.Vectors.VectorFillMode.Both, Main.Job.DrawingFill);
        Assert.Equal("cut", Main.Job.DrawingLayer);
        cut.WaitForAssertion(() => Assert.Contains("% saved", cut.Find("#path-order").TextContent, StringComparison.Ordinal));

        cut.Find($"#{JobViewModel.ToleranceField}").Change("0");

        cut.WaitForAssertion(() => Assert.Contains("chord tolerance 0 µm: must be between", cut.Find($"[data-error={JobViewModel.ToleranceField}]").TextContent, StringComparison.Ordinal));
        Assert.Null(Main.Job.Drawing);
    }

    [Fact]
    public void InvertTicked_ViewModelInvertsTheMask()
    {
        OpenQr();
        var cut = Render<ImagePanel>(p => p.Add(c => c.Job, Main.Job));

        cut.Find("#invert").Change(true);

        Assert.True(Main.Job.Invert);
        // 1118: its thousands grouped by a narrow space, never a comma or a point a decimal-comma lab would misread.
        cut.WaitForAssertion(() => Assert.Equal("1\u202F118", cut.Find("#burn-pixels").TextContent));
    }
}

public sealed class SizePanelTests : ComponentTest
{
    [Fact]
    public void Width_Typed_HeightFollowsTheAspect()
    {
        OpenQr();
        var cut = Render<SizePanel>(p => p.Add(c => c.Job, Main.Job));

        cut.Find("#widthMm").Change("12");

        cut.WaitForAssertion(() => Assert.Equal("12", cut.Find("#heightMm").GetAttribute("value")));
        Assert.Contains("12 × 12 mm", cut.Find("#size-figures").TextContent, StringComparison.Ordinal);
    }

    [Theory]
    [InlineData("widthMm", "1e9", "at most 60 mm")]
    [InlineData("widthMm", "0", "above 0")]
    [InlineData("pitchUm", "1e9", "at most 60000 µm, the travel")]
    public void Size_BeyondTheMachine_RefusedBesideTheField(string field, string value, string expected)
    {
        OpenQr();
        var cut = Render<SizePanel>(p => p.Add(c => c.Job, Main.Job));

        cut.Find("#" + field).Change(value);

        cut.WaitForAssertion(() => Assert.Contains(expected, cut.Find($"[data-error={field}]").TextContent, StringComparison.Ordinal));
        Assert.Null(Main.Job.Job);
    }

    [Fact]
    public void Origin_OffTheStage_Refused()
    {
        OpenQr();
        var cut = Render<SizePanel>(p => p.Add(c => c.Job, Main.Job));

        cut.Find("#originXMm").Change("-3");

        cut.WaitForAssertion(() => Assert.Contains("origin X -3 mm: outside the travel 0..60 mm", cut.Find("[data-error=origin]").TextContent, StringComparison.Ordinal));
    }
}

public sealed class ProcessPanelTests : ComponentTest
{
    [Fact]
    public void BurnSpeed_AboveTheStage_RefusedWithItsUnit()
    {
        OpenQr();
        var cut = Render<ProcessPanel>(p => p.Add(c => c.Job, Main.Job));

        cut.Find("#burnSpeedMmPerS").Change("10");

        cut.WaitForAssertion(() => Assert.Contains("burn speed 10 mm/s: outside what the stage takes, 0.00093..4 mm/s", cut.Find("[data-error=burnSpeedMmPerS]").TextContent, StringComparison.Ordinal));
        Assert.Empty(cut.FindAll("#estimate"));
    }

    [Fact]
    public void Passes_Typed_EstimateCoversThemAll()
    {
        OpenQr();
        var cut = Render<ProcessPanel>(p => p.Add(c => c.Job, Main.Job));
        var one = Main.Job.EstimatedSeconds!.Value;

        cut.Find("#passes").Change("3");

        var statistics = Main.Job.Job!.Statistics;
        Assert.Equal(one + (2 * (statistics.EngravingSeconds + statistics.PassSetupSeconds)), Main.Job.EstimatedSeconds!.Value, 6);
        Assert.Contains("est.", cut.Find("#estimate").TextContent, StringComparison.Ordinal);
    }

    [Fact]
    public void Mode_DotsAndPulsesPerDot_PlannedAsDotsWithNPulsesAPixel()
    {
        OpenQr();
        var cut = Render<ProcessPanel>(p => p.Add(c => c.Job, Main.Job));
        Assert.Empty(cut.FindAll("#pulsesPerDot"));

        cut.Find("#mode").Change("Dots");
        cut.Find("#pulsesPerDot").Change("10");

        var job = Assert.IsType<Core.Jobs.PreparedJob>(Main.Job.Job);
        var dots = Assert.IsType<Core.Planning.DotPlan>(job.Dots);
        Assert.Equal((Core.Planning.PlanMode.Dots, 10), (job.Spec.Process.Mode, job.Spec.Process.PulsesPerDot));
        Assert.Equal(dots.Estimate.TotalSeconds, job.Statistics.EngravingSeconds, 9);
        Assert.Equal(job.Statistics.WholeRunSeconds(), Main.Job.EstimatedSeconds!.Value, 6);
        Assert.Contains("dots", cut.Find("#estimate").TextContent, StringComparison.Ordinal);
        Assert.Contains("10 pulses per pixel", cut.Find("#pulses").TextContent, StringComparison.Ordinal);
        Assert.Equal((Core.Planning.PlanMode.Dots, 10), (Main.Job.ToSettings().Mode, Main.Job.ToSettings().PulsesPerDot));
    }

    [Fact]
    public void PulsesPerDot_Zero_RefusedBesideTheField()
    {
        OpenQr();
        var cut = Render<ProcessPanel>(p => p.Add(c => c.Job, Main.Job));
        cut.Find("#mode").Change("Dots");

        cut.Find("#pulsesPerDot").Change("0");

        cut.WaitForAssertion(() => Assert.Contains("pulses per dot 0: must be 1..1000000", cut.Find("[data-error=pulsesPerDot]").TextContent, StringComparison.Ordinal));
        Assert.Null(Main.Job.Job);
    }

    [Fact]
    public void Raster_PulseFiguresShownLive()
    {
        OpenQr();
        var cut = Render<ProcessPanel>(p => p.Add(c => c.Job, Main.Job));

        cut.Find("#burnSpeedMmPerS").Change("2");

        // 2 mm/s at 1 kHz: pulses 2 µm apart, 90 % of a 20 µm spot overlapped.
        Assert.Contains("pulses 2 µm apart · overlap 90 %", cut.Find("#pulses").TextContent, StringComparison.Ordinal);
        Assert.DoesNotContain("µJ", cut.Find("#pulses").TextContent, StringComparison.Ordinal);

        cut.Find("#pulseEnergyUj").Change("5");

        // 5 mm over 41 px: 121.95 µm pixels, 60.98 pulses of 5 µJ each.
        Assert.Contains("60.98 pulses per pixel · 304.88 µJ per pixel", cut.Find("#pulses").TextContent, StringComparison.Ordinal);
        Assert.Equal(5, Main.Job.ToSettings().PulseEnergyUj);
    }

    [Fact]
    public void PulseEnergy_BelowZeroTyped_TheRulesSentenceBesideItAndEmptyIsNotKnown()
    {
        // Issue 35: the field once dropped 0 and below without a word, which the command line refuses.
        OpenQr();
        var cut = Render<ProcessPanel>(p => p.Add(c => c.Job, Main.Job));

        cut.Find("#pulseEnergyUj").Change("-5");

        Assert.Equal("pulse energy -5 µJ: must be a finite number above 0 (or left out: not known)", cut.Find("[data-error=pulseEnergyUj]").TextContent);
        cut.Find("#pulseEnergyUj").Change("");
        Assert.Empty(cut.FindAll("[data-error=pulseEnergyUj]"));
        Assert.Null(Main.Job.ToSettings().PulseEnergyUj);
        Assert.Equal(string.Empty, cut.Find("#pulseEnergyUj").GetAttribute("value"));
    }
}

public sealed class SweepPanelTests : ComponentTest
{
    [Fact]
    public void Rows_Typed_SummaryOrTheRefusalBesideIt()
    {
        var cut = Render<SweepPanel>(p => p.Add(c => c.Sweep, Main.Sweep));

        cut.Find("#sweepRows").Change("pitch=25,50,100");

        Assert.Contains("3 × 3 cells", cut.Find("#sweep-summary").TextContent, StringComparison.Ordinal);

        cut.Find("#sweepColumns").Change("pitch=10");

        Assert.Contains("both vary pitch", cut.Find("[data-error=sweep]").TextContent, StringComparison.Ordinal);
        Assert.False(Main.Sweep.RunSweepCommand.CanExecute(null));
    }

    [Fact]
    public void TwoAxisMachine_NoFocalSeriesButtonAndANoteWhy()
    {
        var cut = Render<SweepPanel>(p => p.Add(c => c.Sweep, Main.Sweep));

        Assert.Empty(cut.FindAll("#sweepFocalSeries"));
        Assert.Contains("no Z axis", cut.Find("#sweep-focus-note").TextContent, StringComparison.Ordinal);
        Assert.DoesNotContain("focus", cut.Find("label[for=sweepRows]").TextContent, StringComparison.Ordinal);
    }

    [Fact]
    public void ProfileWithZ_FocalSeriesButton_FillsTheRowsWithTheFocus()
    {
        var cut = Render<SweepPanel>(p => p.Add(c => c.Sweep, Main.Sweep));

        Main.Job.UseProfile(Core.Geometry.MachineProfile.Default with { Z = new Core.Geometry.ZAxisProfile() });
        cut.Find("#sweepFocalSeries").Click();

        Assert.Equal("focus=-200..200:50", cut.Find("#sweepRows").GetAttribute("value"));
        Assert.Contains("9 × 1 cells", cut.Find("#sweep-summary").TextContent, StringComparison.Ordinal);
        Assert.Contains("focus", cut.Find("label[for=sweepRows]").TextContent, StringComparison.Ordinal);
        Assert.Contains("µm from the visible focus (Z 12.5 mm)", cut.Find("#sweep-focus-note").TextContent, StringComparison.Ordinal);
    }
}


public sealed class CalibrationPanelTests : ComponentTest
{
    [Fact]
    public void Measurements_SolvedAndStored_TheJobIsCompensatedFromNowOn()
    {
        OpenQr();
        var cut = Render<CalibrationPanel>(p => p.Add(c => c.Calibration, Calibration));
        Assert.Contains("not calibrated", cut.Find("#calibration-current").TextContent, StringComparison.Ordinal);
        Assert.True(cut.Find("#calStore").HasAttribute("disabled"));

        // The command line's worked example: X 16 mm measured 16.008, Y 15.992, the grooves at 90.5°.
        cut.Find("#calXMeasured").Change("16.0080");
        cut.Find("#calYMeasured").Change("15.9920");
        cut.Find("#calAngle").Change("90.5");
        cut.Find("#calSolve").Click();

        Assert.Contains("squareness +0.5000°, scale X +500.0 ppm, scale Y -500.0 ppm", cut.FindAll("[data-solution=line]")[0].TextContent, StringComparison.Ordinal);
        cut.Find("#calStore").Click();

        var calibration = Assert.IsType<Core.Geometry.AxisCalibration>(Main.Job.Profile.Calibration);
        Assert.Equal(500, calibration.ScaleXPpm, 6);
        Assert.Equal(0.5, calibration.SquarenessDegrees, 6);
        var path = Path.Combine(DataFolder.Path, "machine-profile.json");
        Assert.Equal(calibration, Core.Geometry.MachineProfile.Load(path).Calibration);
        Assert.Same(Main.Job.Profile, Main.Machine.Profile);
        Assert.NotEqual(1.0, Main.Job.Job!.Geometry.Geometry.Compensation.XPerX);
        Assert.Contains("scale X +500.0 ppm", cut.Find("#calibration-current").TextContent, StringComparison.Ordinal);

        cut.Find("#calClear").Click();

        Assert.Null(Main.Job.Profile.Calibration);
        Assert.Null(Core.Geometry.MachineProfile.Load(path).Calibration);
    }

    [Fact]
    public void LoadPattern_OpensItAsTheJobAtItsPitch()
    {
        var cut = Render<CalibrationPanel>(p => p.Add(c => c.Calibration, Calibration));

        cut.Find("#calLoadPattern").Click();

        Assert.StartsWith("calibration-pattern-20mm-10um", Path.GetFileName(Main.Job.ImagePath), StringComparison.Ordinal);
        Assert.Equal(10, Main.Job.Job!.Geometry.PitchUm, 9);
        Assert.Contains("Scale marks every", cut.Markup, StringComparison.Ordinal);
    }

    [Fact]
    public void Solve_NothingMeasured_RefusedWithOneLine()
    {
        var cut = Render<CalibrationPanel>(p => p.Add(c => c.Calibration, Calibration));

        cut.Find("#calSolve").Click();

        Assert.False(string.IsNullOrWhiteSpace(cut.Find("[data-error=calibration]").TextContent));
        Assert.Null(Calibration.Solution);
    }
}

public sealed class AlignmentPanelTests : ComponentTest
{
    private static (double X, double Y) OnStage(double x, double y, double degrees)
    {
        // A sample turned by `degrees` with the job's corner at 20, 15 mm.
        var a = degrees * Math.PI / 180;
        return (20 + (x * Math.Cos(a)) - (y * Math.Sin(a)), 15 + (x * Math.Sin(a)) + (y * Math.Cos(a)));
    }

    private static void Mark(IRenderedComponent<AlignmentPanel> cut, int mark, double jobX, double jobY, (double X, double Y) stage)
    {
        cut.Find($"#alJob{mark}X").Change(jobX.ToString(System.Globalization.CultureInfo.InvariantCulture));
        cut.Find($"#alJob{mark}Y").Change(jobY.ToString(System.Globalization.CultureInfo.InvariantCulture));
        cut.Find($"#alStage{mark}X").Change(stage.X.ToString("R", System.Globalization.CultureInfo.InvariantCulture));
        cut.Find($"#alStage{mark}Y").Change(stage.Y.ToString("R", System.Globalization.CultureInfo.InvariantCulture));
    }

    [Fact]
    public void Align_MarksOfASampleTurnedTwoDegrees_TheJobRotatedOntoThem()
    {
        OpenQr();
        var pitch = Main.Job.Job!.Geometry.PitchUm;
        var cut = Render<AlignmentPanel>(p => p.Add(c => c.Alignment, Alignment));
        Mark(cut, 1, 1, 1, OnStage(1, 1, 2));
        Mark(cut, 2, 4, 4, OnStage(4, 4, 2));

        cut.Find("#alAlign").Click();

        Assert.Contains("Rotation: +2°", cut.FindAll("[data-alignment=line]")[0].TextContent, StringComparison.Ordinal);
        Assert.EndsWith("-aligned.png", Main.Job.ImagePath, StringComparison.Ordinal);
        Assert.Equal(pitch, Main.Job.Job!.Geometry.PitchUm, 6);

        // The rotated QR code is wider than 41 px, and its box starts left of the job's corner (the turn moves its left edge in -X).
        Assert.True(Main.Job.Mask!.Width > 41);
        Assert.True(Main.Job.OriginXMm < 20 && Main.Job.OriginYMm <= 15.0001, $"origin {Main.Job.OriginXMm}, {Main.Job.OriginYMm}");
    }

    [Fact]
    public void Align_TurnedJob_TheAlignedImageIsNotTurnedAgain()
    {
        Assert.True(Main.Job.LoadImage(TestFiles.Asset("text-banner.png")));
        Main.Job.Rotate(clockwise: true);
        var cut = Render<AlignmentPanel>(p => p.Add(c => c.Alignment, Alignment));
        Mark(cut, 1, 0.5, 0.5, OnStage(0.5, 0.5, 0));
        Mark(cut, 2, 1, 4, OnStage(1, 4, 0));

        cut.Find("#alAlign").Click();

        // The aligned mask is the turned job's (taller than wide): shown and burned upright as it was written.
        Assert.EndsWith("-aligned.png", Main.Job.ImagePath, StringComparison.Ordinal);
        Assert.Equal(0, Main.Job.QuarterTurns);
        Assert.True(Main.Job.Mask!.Height > Main.Job.Mask.Width, $"{Main.Job.Mask.Width} × {Main.Job.Mask.Height}");
    }

    [Fact]
    public void Align_MarksFartherApartOnTheStage_RefusedWithOneLine()
    {
        OpenQr();
        var cut = Render<AlignmentPanel>(p => p.Add(c => c.Alignment, Alignment));
        Mark(cut, 1, 1, 1, (21, 16));
        Mark(cut, 2, 4, 4, (24.2, 19));

        cut.Find("#alAlign").Click();

        Assert.False(string.IsNullOrWhiteSpace(cut.Find("[data-error=alignment]").TextContent));
        Assert.EndsWith("qr-code.bmp", Main.Job.ImagePath, StringComparison.Ordinal);
    }

    [Fact]
    public void TakeStagePosition_NotConnected_SaysWhatToDo()
    {
        var cut = Render<AlignmentPanel>(p => p.Add(c => c.Alignment, Alignment));

        cut.Find("#alTake1").Click();

        Assert.Contains("connect, home and jog onto the mark first", cut.Find("[data-error=alignment]").TextContent, StringComparison.Ordinal);
    }
}
