using Bunit;
using LaserEngrave.App.Components.Workspace;
using LaserEngrave.App.Services;
using LaserEngrave.App.ViewModels;
using LaserEngrave.Core.Camera;
using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Logging;
using LaserEngrave.Devices.Abstractions;
using LaserEngrave.Devices.Machine;
using LaserEngrave.Simulator;
using LaserEngrave.Simulator.Burn;
using LaserEngrave.Simulator.Camera;
using NSubstitute;

namespace LaserEngrave.App.Tests.Components;

/// <summary>
/// The Camera panel's focus sweep on the simulator with a Z axis, and the live camera's frames sent to the app: calibration
/// from frames a page would send (here a fake frame source rendering the twin where the stage stands), on a connection the
/// app takes for a real machine (issue 37).
/// </summary>
public sealed class CameraFocusAndLiveTests : ComponentTest
{
    // The twin's camera, 320 x 240 as the simulator's default is 640 x 480 (the panel's default optics).
    private static readonly CameraProfile Optics = new() { WidthPx = 320, HeightPx = 240, UmPerPixel = 1.37, RotationDeg = 2.3, SpotOffsetXUm = 23, SpotOffsetYUm = -14 };

    private readonly StepClock _clock = new();
    private SimulatedMachine? _twin;

    private void UseSimulator(MachineProfile profile, bool hideTwin)
    {
        var path = Path.Combine(DataFolder.Path, "profile.json");
        profile.Save(path);
        Main.UseProfile(path, profile);
        var factory = new MachineConnectionFactory(new SimulatorOptions());
        Machine.Factory.ConnectAsync(Arg.Any<MachineChoice>(), Arg.Any<MachineProfile>(), Arg.Any<CancellationToken>())
            .Returns(async c =>
            {
                var connection = await factory.ConnectAsync(c.Arg<MachineChoice>(), c.Arg<MachineProfile>(), c.Arg<CancellationToken>());
                _twin = ((BurnInspector)connection.Inspector!).Machine;
                return hideTwin ? new NotATwin(connection) : connection;
            });
    }

    private async Task AtAsync(double xMm, double yMm)
    {
        await ConnectAsync();
        Main.TestMoves.GoToXMm = xMm;
        Main.TestMoves.GoToYMm = yMm;
        await Main.TestMoves.GoToCommand.ExecuteAsync(null);
        Assert.Null(Main.TestMoves.Error);
    }

    [Fact]
    public async Task FindFocus_SimulatorWithZ_EveryStepShownAndTheSharpestWithinOneStepThenOffered()
    {
        UseSimulator(MachineProfile.Default with { Camera = Optics, Z = new ZAxisProfile() }, hideTwin: false);
        await AtAsync(30, 30);
        var cut = Render<CameraPanel>(p => p.Add(c => c.Camera, Camera));

        cut.Find("#camera-find-focus").Click();

        cut.WaitForAssertion(() => Assert.True(cut.FindAll("[data-camera=focus]").Count == 2 || cut.FindAll("[data-error=camera]").Count > 0), TimeSpan.FromSeconds(120));
        Assert.Empty(cut.FindAll("[data-error=camera]").Select(e => e.TextContent));
        // -300..300 µm by 50: thirteen steps, each with its sharpness; the sharpest marked.
        Assert.Equal(13, cut.FindAll("#camera-focus-steps tbody tr").Count);
        var truth = new TwinCameraOptions().CameraFocusOffsetUm;
        var result = Camera.FocusResult!;
        Xunit.TestContext.Current.TestOutputHelper?.WriteLine($"panel's focus sweep: sharpest step {result.BestStepUm} µm, peak {result.BestOffsetUm:F1} µm, the twin's focus {truth} µm; {string.Join(", ", result.Points.Select(p => $"{p.OffsetUm}:{p.Sharpness:F1}"))}");
        Assert.True(Math.Abs(result.BestStepUm - truth) <= 50, $"sharpest step {result.BestStepUm} µm, the twin's focus {truth} µm");
        Assert.Equal(result.BestStepUm.ToString(System.Globalization.CultureInfo.InvariantCulture), cut.Find("#camera-focus-steps tr.best").GetAttribute("data-focus-step"));
        Assert.Contains("focal-offset series (Sweep panel", cut.FindAll("[data-camera=focus]")[1].TextContent, StringComparison.Ordinal);

        cut.Find("#camera-focus-go").Click();

        cut.WaitForAssertion(() => Assert.StartsWith("Z at ", cut.Find("#camera-goto").TextContent, StringComparison.Ordinal), TimeSpan.FromSeconds(60));
        // The twin's Z stands at the peak the sweep found, within a microstep: the camera is that far from its focus.
        var defocus = new TwinCamera(_twin!).DefocusUm();
        Assert.Equal(Camera.SharpestFocusUm!.Value - truth, defocus, 0.2);
        Assert.Null(Main.Machine.Error);
    }

    [Fact]
    public void FindFocus_ProfileWithoutZ_PanelSaysWhyNot()
    {
        var profile = MachineProfile.Default with { Camera = Optics };
        Main.UseProfile(Path.Combine(DataFolder.Path, "no-z.json"), profile);
        Camera.Refresh();

        var cut = Render<CameraPanel>(p => p.Add(c => c.Camera, Camera));

        Assert.Empty(cut.FindAll("#camera-find-focus"));
        Assert.StartsWith("No focus sweep: this machine profile has no focus (Z) axis, so there is no Z to sweep", cut.Find("#camera-focus-none").TextContent, StringComparison.Ordinal);
    }

    [Fact]
    public async Task Calibrate_LiveFramesFromThePage_MeasuresTheCameraLikeTheTwin()
    {
        var camera = new CameraViewModel(new CameraService(Main, _clock));
        UseSimulator(MachineProfile.Default with { Camera = Optics }, hideTwin: true);
        await AtAsync(30, 30);
        Assert.False(camera.IsTwin);
        // One camera, so each frame has noise of its own (the same frame number twice is the same noise, a fixed pattern that does not move with the stage).
        TwinCamera? twinCamera = null;
        var page = new FakePage(camera, _clock, () => (twinCamera ??= new TwinCamera(_twin!, optics: Optics)).Capture());
        camera.ReportLiveCamera("fake camera", null);
        var cut = Render<CameraPanel>(p => p.Add(c => c.Camera, camera));

        cut.Find("#camera-calibrate").Click();

        cut.WaitForAssertion(() => Assert.True(cut.FindAll("[data-camera=calibration]").Count == 4 || cut.FindAll("[data-error=camera]").Count > 0), TimeSpan.FromSeconds(120));
        Assert.Empty(cut.FindAll("[data-error=camera]").Select(e => e.TextContent));
        var measured = camera.InForce!;
        var truth = Optics.Nominal;
        var scaleErrorPercent = 100 * ((measured.UmPerPixel / truth.UmPerPixel) - 1);
        var rotationErrorDeg = measured.RotationDeg - truth.RotationDeg;
        var spotErrorUm = Math.Sqrt(Math.Pow(measured.SpotXPx - truth.SpotXPx, 2) + Math.Pow(measured.SpotYPx - truth.SpotYPx, 2)) * truth.UmPerPixel;
        Xunit.TestContext.Current.TestOutputHelper?.WriteLine($"live frames: {page.Sent} sent, scale error {scaleErrorPercent:F4} %, rotation error {rotationErrorDeg:F4}°, spot error {spotErrorUm:F3} µm, residual {measured.ResidualUm:F3} µm");
        Assert.True(Math.Abs(scaleErrorPercent) < 0.5, $"scale off by {scaleErrorPercent:F3} %");
        Assert.True(Math.Abs(rotationErrorDeg) < 0.1, $"rotation off by {rotationErrorDeg:F3}°");
        Assert.True(spotErrorUm < 2, $"spot off by {spotErrorUm:F2} µm");
        Assert.True(page.Sent >= 9, $"{page.Sent} frames");
        Assert.Equal($"Frames measured here: {page.Sent} (320 x 240 grey)", cut.Find("#camera-live-frames").TextContent);
    }

    [Fact]
    public async Task PickMark_TwoMarksClickedInLiveFrames_GivenToTheAlignmentWhichPlacesTheJobWithinFiveMicrometres()
    {
        var camera = new CameraViewModel(new CameraService(Main, _clock), (mark, x, y) =>
        {
            if (mark == 1)
            {
                (Alignment.Stage1XMm, Alignment.Stage1YMm) = (x, y);
            }
            else
            {
                (Alignment.Stage2XMm, Alignment.Stage2YMm) = (x, y);
            }
        });
        UseSimulator(MachineProfile.Default with { Camera = Optics }, hideTwin: true);
        await AtAsync(30, 30);
        TwinCamera? twinCamera = null;
        _ = new FakePage(camera, _clock, () => (twinCamera ??= new TwinCamera(_twin!, optics: Optics)).Capture());
        camera.ReportLiveCamera("fake camera", null);
        await camera.CalibrateCommand.ExecuteAsync(null);
        Assert.Null(camera.Error);
        var cut = Render<CameraPanel>(p => p.Add(c => c.Camera, camera));
        // The sample's marks: where a job turned by 7.3° has its marks (1, 1.5) and (9, 6.5) mm.
        var truth = new Core.Alignment.RigidTransform(7.3 * Math.PI / 180, 24.2, 25.7);
        (double X, double Y)[] jobMarks = [(1.0, 1.5), (9.0, 6.5)];
        var marks = jobMarks.Select(m => truth.Apply(m.X, m.Y)).ToList();
        foreach (var (sx, sy) in marks)
        {
            twinCamera!.AddMark(sx * 1000, sy * 1000, 40);
        }

        for (var i = 0; i < 2; i++)
        {
            // Jog near the mark (80 µm off, as by eye), press Pick mark, click near it in the image.
            var (sx, sy) = marks[i];
            Main.TestMoves.GoToXMm = sx + 0.08;
            Main.TestMoves.GoToYMm = sy - 0.06;
            await Main.TestMoves.GoToCommand.ExecuteAsync(null);
            var (px, py) = Optics.Nominal.PixelAt(-80, 60);
            // Offered once the panel has seen the move end (the machine held no more).
            cut.WaitForAssertion(() => Assert.False(cut.Find($"#camera-pick-{i + 1}").HasAttribute("disabled")), TimeSpan.FromSeconds(10));
            // Pressed again, as a person would, when the press met the button disabled for a moment (the panel disables
            // it while the machine is held, which the twin camera's frames do briefly): one press that lands is needed.
            cut.WaitForAssertion(
                () =>
                {
                    if (camera.PickingMark is null && !cut.Find($"#camera-pick-{i + 1}").HasAttribute("disabled"))
                    {
                        cut.Find($"#camera-pick-{i + 1}").Click();
                    }

                    Assert.Equal(i + 1, camera.PickingMark);
                },
                TimeSpan.FromSeconds(10));
            await cut.InvokeAsync(() => cut.Instance.OnCameraClick(Math.Round(px) - 2, Math.Round(py) + 4));
            cut.WaitForAssertion(() => Assert.True(camera.PickingMark is null || camera.Error is not null), TimeSpan.FromSeconds(30));
            Assert.Null(camera.Error);
        }

        (Alignment.Job1XMm, Alignment.Job1YMm, Alignment.Job2XMm, Alignment.Job2YMm) = (jobMarks[0].X, jobMarks[0].Y, jobMarks[1].X, jobMarks[1].Y);
        var alignment = Core.Alignment.FiducialAlignment.Solve(
            new Core.Alignment.Fiducial(Alignment.Job1XMm, Alignment.Job1YMm, Alignment.Stage1XMm, Alignment.Stage1YMm),
            new Core.Alignment.Fiducial(Alignment.Job2XMm, Alignment.Job2YMm, Alignment.Stage2XMm, Alignment.Stage2YMm));
        var worst = 0.0;
        foreach (var (jx, jy) in new[] { (0.0, 0.0), (10.0, 0.0), (0.0, 8.0), (10.0, 8.0), jobMarks[0], jobMarks[1] })
        {
            var (ax, ay) = alignment.Transform.Apply(jx, jy);
            var (tx, ty) = truth.Apply(jx, jy);
            worst = Math.Max(worst, 1000 * Math.Sqrt(Math.Pow(ax - tx, 2) + Math.Pow(ay - ty, 2)));
        }

        Xunit.TestContext.Current.TestOutputHelper?.WriteLine($"marks picked in live frames: worst {worst:F3} µm over the job's corners and marks, rotation {alignment.Transform.AngleDegrees:F4}° (true 7.3°)");
        Assert.True(worst < 5, $"the aligned job is up to {worst:F2} µm off");
        Assert.StartsWith("Mark 2: stage ", cut.Find("#camera-mark").TextContent, StringComparison.Ordinal);
    }

    [Fact]
    public async Task Calibrate_LiveFramesWithoutTexture_RefusedWithAPlainSentence()
    {
        var camera = new CameraViewModel(new CameraService(Main, _clock));
        UseSimulator(MachineProfile.Default with { Camera = Optics }, hideTwin: true);
        await AtAsync(30, 30);
        var page = new FakePage(camera, _clock, () => new CameraFrame(320, 240, Enumerable.Range(0, 320 * 240).Select(i => (byte)(120 + (i % 2))).ToArray()));
        camera.ReportLiveCamera("fake camera", null);
        var cut = Render<CameraPanel>(p => p.Add(c => c.Camera, camera));

        cut.Find("#camera-calibrate").Click();

        cut.WaitForAssertion(() => Assert.Single(cut.FindAll("[data-error=camera]")), TimeSpan.FromSeconds(60));
        Assert.StartsWith("the image has too little texture to track", cut.Find("[data-error=camera]").TextContent, StringComparison.Ordinal);
        Assert.Empty(_twin!.Recorder.LaserOnIntervals(_twin.NowSeconds));
    }

    [Fact]
    public void SubmitLiveFrame_WrongSizeLengthOrTooSoon_RefusedAndSaid()
    {
        var camera = new CameraViewModel(new CameraService(Main, _clock));
        Main.UseProfile(Path.Combine(DataFolder.Path, "camera.json"), MachineProfile.Default with { Camera = Optics });
        var good = new byte[320 * 240];

        Assert.False(camera.SubmitLiveFrame(640, 480, new byte[640 * 480]));
        Assert.Equal("a live frame of 640 x 480 pixels is not the 320 x 240 the camera's profile asks for", camera.Error);
        Assert.False(camera.SubmitLiveFrame(320, 240, new byte[100]));
        Assert.Equal("a live frame of 320 x 240 pixels came with 100 bytes, not 76800", camera.Error);
        Assert.True(camera.SubmitLiveFrame(320, 240, good));
        _clock.Advance(TimeSpan.FromMilliseconds(50));
        Assert.False(camera.SubmitLiveFrame(320, 240, good));
        Assert.Equal("live frames came faster than one every 100 ms; this one was dropped", camera.Error);
        _clock.Advance(TimeSpan.FromMilliseconds(60));
        Assert.True(camera.SubmitLiveFrame(320, 240, good));
        Assert.Equal(2, camera.LiveFramesReceived);
    }

    [Fact]
    public void LiveFrameSize_LargeCamera_ShrunkByAWholeFactorToAtMost640By480()
    {
        var camera = new CameraViewModel(new CameraService(Main, _clock));
        Main.UseProfile(Path.Combine(DataFolder.Path, "big.json"), MachineProfile.Default with { Camera = new CameraProfile { WidthPx = 1920, HeightPx = 1080 } });

        Assert.Equal((640, 360), camera.LiveFrameSize);
    }

    [Fact]
    public async Task CaptureAsync_FrameShrunkByThePage_EnlargedToTheProfilesPixels()
    {
        var service = new CameraService(Main, _clock);
        Main.UseProfile(Path.Combine(DataFolder.Path, "big.json"), MachineProfile.Default with { Camera = new CameraProfile { WidthPx = 1920, HeightPx = 1080 } });
        // A ramp along x, 640 x 360 as the page sends a 1920 x 1080 camera: two grey levels a sent pixel.
        var sent = new byte[640 * 360];
        for (var i = 0; i < sent.Length; i++)
        {
            sent[i] = (byte)(i % 640 / 5);
        }

        service.LiveFrameWanted += (_, _) => Assert.Null(service.SubmitLiveFrame(640, 360, sent));

        var frame = await service.CaptureAsync(Xunit.TestContext.Current.CancellationToken);

        Assert.Equal((1920, 1080), (frame.Width, frame.Height));
        // Camera pixel 3k + 1 is the middle of sent pixel k: its value again.
        Assert.Equal(sent[100], frame[301, 500]);
        Assert.Equal(sent[600], frame[1801, 10]);
    }

    // What the page does when the app asks for a frame: the camera's next frame, grey, sent back (the clock moves on as a camera's would).
    private sealed class FakePage
    {
        public FakePage(CameraViewModel camera, StepClock clock, Func<CameraFrame> take)
        {
            camera.LiveFrameWanted += (_, _) =>
            {
                clock.Advance(TimeSpan.FromMilliseconds(200));
                var frame = take();
                if (camera.SubmitLiveFrame(frame.Width, frame.Height, frame.Pixels))
                {
                    Sent++;
                }
            };
        }

        public int Sent { get; private set; }
    }

    // A clock that moves only when told: the live frames' rate is judged by it.
    private sealed class StepClock : TimeProvider
    {
        private long _ticks = TimeSpan.TicksPerDay;

        public override long TimestampFrequency => TimeSpan.TicksPerSecond;

        public override long GetTimestamp() => Interlocked.Read(ref _ticks);

        public void Advance(TimeSpan by) => Interlocked.Add(ref _ticks, by.Ticks);
    }
}

// The simulator's connection with its burn inspector hidden: the app takes it for a real machine, so frames come from the page.
internal sealed class NotATwin(IMachineConnection inner) : IMachineConnection
{
    public string Description => inner.Description;

    public MachineProfile Profile => inner.Profile;

    public TimeProvider TimeProvider => inner.TimeProvider;

    public bool IsSimulated => inner.IsSimulated;

    public IStage Stage => inner.Stage;

    public ILaserGate Gate => inner.Gate;

    public ILatencyProbe Latency => inner.Latency;

    public IRunInspector? Inspector => null;

    public ValueTask DisposeAsync() => inner.DisposeAsync();
}
