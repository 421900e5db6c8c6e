using System.Globalization;
using CommunityToolkit.Mvvm.ComponentModel;
using CommunityToolkit.Mvvm.Input;
using LaserEngrave.App.Services;
using LaserEngrave.Core.Camera;
using LaserEngrave.Core.Geometry;

namespace LaserEngrave.App.ViewModels;

/// <summary>The Camera view: the image (a camera in the page, or the twin's), the spot, a scale bar, the job's outline, click to go, calibrate, the focus figure.</summary>
/// <remarks>
/// Everything drawn over the image is in camera pixels, from the calibration in force (the measured one, else the
/// profile's nominal optics): the spot's pixel, the scale bar's length, the job's corners. A click is a camera pixel;
/// <see cref="CameraCalibration.StageTargetUm"/> turns it into the stage position that brings it under the spot.
/// </remarks>
public sealed partial class CameraViewModel : ObservableObject
{
    private readonly ICameraService _camera;
    private readonly Lock _refreshLock = new();
    private object? _shown;
    private int _refreshState; // 0 idle, 1 refreshing, 2 refreshing and asked again

    private readonly Action<int, double, double>? _takeMark;

    /// <param name="takeMark">Where a mark picked in the image goes: mark 1 or 2 and its stage position, mm (the Alignment panel's fields).</param>
    public CameraViewModel(ICameraService camera, Action<int, double, double>? takeMark = null)
    {
        ArgumentNullException.ThrowIfNull(camera);
        _camera = camera;
        _takeMark = takeMark;
        // A change is reported on the machine's own thread (the simulation's loop on the twin): the twin's frame is rendered
        // on the thread pool instead, at most one at a time, so the machine never waits for a picture.
        camera.Changed += (_, _) => RefreshSoon();
        Refresh();
    }

    /// <summary>The camera's figures; null: the profile has no camera and the app is not on the simulator.</summary>
    public CameraProfile? Camera => _camera.Camera;

    public bool HasCamera => Camera is not null;

    /// <summary>Frames come from the twin (served as images) rather than from a camera in the page.</summary>
    public bool IsTwin => _camera.IsTwin;

    public int WidthPx => Camera?.WidthPx ?? 640;

    public int HeightPx => Camera?.HeightPx ?? 480;

    /// <summary>The figures in force, measured or nominal.</summary>
    public CameraCalibration? InForce => Camera?.InForce;

    public bool IsCalibrated => Camera?.Calibration is not null;

    /// <summary>The twin's latest frame as a PNG data URL; null with a live camera.</summary>
    [ObservableProperty]
    public partial string? TwinFrameUrl { get; private set; }

    /// <summary>The sharpness figure (<see cref="FocusMeasure"/>) of the latest frame; higher is sharper.</summary>
    [ObservableProperty]
    public partial double? Sharpness { get; private set; }

    /// <summary>The live camera's name, as the page reported it.</summary>
    [ObservableProperty]
    public partial string? LiveCamera { get; private set; }

    [ObservableProperty]
    public partial string? Error { get; private set; }

    /// <summary>What the last calibration measured, one line each.</summary>
    [ObservableProperty]
    public partial IReadOnlyList<string> CalibrationLines { get; private set; } = [];

    /// <summary>Where the last click sent the stage, in words.</summary>
    [ObservableProperty]
    public partial string? LastGoTo { get; private set; }

    /// <summary>The scale bar: a round length, µm, about a fifth of the image wide, and its length in camera pixels.</summary>
    public (double Um, double Px) ScaleBar
    {
        get
        {
            var umPerPixel = InForce?.UmPerPixel ?? 1;
            var target = WidthPx * umPerPixel / 5;
            var decade = Math.Pow(10, Math.Floor(Math.Log10(target)));
            var um = new[] { 5, 2, 1 }.Select(m => m * decade).First(v => v <= target);
            return (um, um / umPerPixel);
        }
    }

    /// <summary>The job's rectangle as SVG points in camera pixels ("x,y x,y ..."); null without a job or a stage position.</summary>
    public string? JobOutline
    {
        get
        {
            if (InForce is not { } calibration || _camera.StagePositionUm is not { } stage || _camera.JobBoxUm is not { } box)
            {
                return null;
            }

            var corners = new[] { (box.Left, box.Top), (box.Right, box.Top), (box.Right, box.Bottom), (box.Left, box.Bottom) };
            return string.Join(' ', corners.Select(c =>
            {
                var (x, y) = calibration.PixelAt(c.Item1 - stage.XUm, c.Item2 - stage.YUm);
                return string.Create(CultureInfo.InvariantCulture, $"{x:0.#},{y:0.#}");
            }));
        }
    }

    public string CalibrationText => InForce is not { } c ? "No camera: the machine profile has no camera section (docs/camera.md)."
        : string.Create(CultureInfo.InvariantCulture, $"{(IsCalibrated ? "Calibrated" : "Not calibrated (the profile's nominal optics)")}: {c.UmPerPixel:0.####} µm a pixel, turned {Degrees(c.RotationDeg):0.###}°{(c.Mirrored ? ", mirrored" : string.Empty)}, spot at {c.SpotXPx:0.#}, {c.SpotYPx:0.#} px{(IsCalibrated ? $", residual {c.ResidualUm:0.###} µm" : string.Empty)}");

    /// <summary>Why Calibrate cannot run now; null when it can.</summary>
    public string? CalibrateUnavailableReason => !HasCamera ? "the machine profile has no camera section"
        : !IsTwin && !_camera.LiveCameraReady ? "the live camera is not playing yet: allow the browser to use it"
        : !_camera.CanMove ? "connect the machine first, and wait for what holds it"
        : null;

    public bool CanGo => HasCamera && _camera.CanMove && _camera.StagePositionUm is not null;

    public bool CanCalibrate => CalibrateUnavailableReason is null;

    /// <summary>The page's camera started (its label) or failed (its error, one line).</summary>
    public void ReportLiveCamera(string? label, string? error)
    {
        LiveCamera = label;
        Error = error;
        _camera.LiveCameraReady = label is not null;
        _shown = null;
        Refresh();
    }

    /// <summary>Raised when a measurement wants a frame of the live camera; the page answers with <see cref="SubmitLiveFrame"/>.</summary>
    public event EventHandler? LiveFrameWanted
    {
        add => _camera.LiveFrameWanted += value;
        remove => _camera.LiveFrameWanted -= value;
    }

    /// <summary>The size the page sends live frames at (the profile's image, shrunk by a whole factor to at most 640 x 480).</summary>
    public (int Width, int Height) LiveFrameSize => _camera.LiveFrameSize;

    /// <summary>A grey frame of the live camera from the page; a refused one (wrong size, too soon) is said in <see cref="Error"/>.</summary>
    public bool SubmitLiveFrame(int width, int height, byte[] grey)
    {
        if (_camera.SubmitLiveFrame(width, height, grey) is { } refusal)
        {
            Error = refusal;
            return false;
        }

        LiveFramesReceived++;
        LiveFramesText = $"Frames measured here: {LiveFramesReceived} ({width} x {height} grey)";
        return true;
    }

    /// <summary>Live frames the page sent that were taken.</summary>
    public int LiveFramesReceived { get; private set; }

    /// <summary>How many live frames the app measured, and their size; null before the first.</summary>
    [ObservableProperty]
    public partial string? LiveFramesText { get; private set; }

    /// <summary>The focus sweep's range and step, µm from the visible focus (z.focusMm, the 0 of the focal-offset series).</summary>
    [ObservableProperty]
    public partial double FocusFromUm { get; set; } = -300;

    /// <inheritdoc cref="FocusFromUm"/>
    [ObservableProperty]
    public partial double FocusToUm { get; set; } = 300;

    /// <inheritdoc cref="FocusFromUm"/>
    [ObservableProperty]
    public partial double FocusStepUm { get; set; } = 50;

    /// <summary>The sweep's steps so far (they arrive while it runs).</summary>
    [ObservableProperty]
    public partial IReadOnlyList<FocusPoint> FocusPoints { get; private set; } = [];

    /// <summary>The last finished sweep; null before one.</summary>
    [ObservableProperty]
    public partial FocusSweepResult? FocusResult { get; private set; }

    /// <summary>What the last sweep found and how it relates to the focal-offset series, one line each.</summary>
    [ObservableProperty]
    public partial IReadOnlyList<string> FocusLines { get; private set; } = [];

    public bool HasFocusAxis => _camera.FocusAxis is not null;

    /// <summary>Why Find focus cannot run now; null when it can.</summary>
    public string? FocusUnavailableReason => !HasCamera ? "the machine profile has no camera section"
        : _camera.FocusAxis is null ? "this machine profile has no focus (Z) axis, so there is no Z to sweep (add a \"z\" section, docs/machine-profile.md); turn the focus by hand and watch the sharpness figure"
        : !IsTwin && !_camera.LiveCameraReady ? "the live camera is not playing yet: allow the browser to use it"
        : !_camera.CanMove ? "connect the machine first, and wait for what holds it"
        : !(FocusStepUm > 0 && FocusToUm > FocusFromUm) ? string.Create(CultureInfo.InvariantCulture, $"the sweep needs a range from a lower to a higher offset and a step above 0 µm (got {FocusFromUm} to {FocusToUm} µm by {FocusStepUm} µm)")
        : _camera.FocusAxis.OffsetProblem(FocusFromUm) is { } low ? string.Create(CultureInfo.InvariantCulture, $"the sweep's start, {FocusFromUm} µm, {low}")
        : _camera.FocusAxis.OffsetProblem(FocusToUm) is { } high ? string.Create(CultureInfo.InvariantCulture, $"the sweep's end, {FocusToUm} µm, {high}")
        : null;

    public bool CanFindFocus => FocusUnavailableReason is null;

    /// <summary>The sharpest Z the last sweep found (between steps), µm from the visible focus; offered by <see cref="GoToSharpestFocusCommand"/>.</summary>
    public double? SharpestFocusUm => FocusResult is { } r ? Math.Round(r.BestOffsetUm, 1) + 0.0 : null;

    public bool CanGoToSharpestFocus => SharpestFocusUm is not null && HasFocusAxis && _camera.CanMove;

    partial void OnFocusFromUmChanged(double value) => FindFocusCommand.NotifyCanExecuteChanged();

    partial void OnFocusToUmChanged(double value) => FindFocusCommand.NotifyCanExecuteChanged();

    partial void OnFocusStepUmChanged(double value) => FindFocusCommand.NotifyCanExecuteChanged();

    /// <summary>Steps Z through the range with the laser off, measuring the sharpness at each step; Z goes back where it stood.</summary>
    [RelayCommand(CanExecute = nameof(CanFindFocus))]
    private async Task FindFocusAsync(CancellationToken cancellationToken)
    {
        Error = null;
        FocusResult = null;
        FocusLines = [];
        FocusPoints = [];
        var z = _camera.FocusAxis;
        try
        {
            var result = await _camera.FindFocusAsync(FocusFromUm, FocusToUm, FocusStepUm, new Steps(this), cancellationToken);
            FocusPoints = result.Points;
            FocusResult = result;
            if (z is not null)
            {
                var peak = SharpestFocusUm!.Value;
                FocusLines =
                [
                    string.Create(CultureInfo.InvariantCulture, $"Sharpest step: {result.BestStepUm:+0.#;-0.#;0} µm from the visible focus (Z {z.FocusMm + Units.UmToMm(result.BestStepUm):0.####} mm); between the steps the peak is at {peak:+0.#;-0.#;0} µm"),
                    string.Create(CultureInfo.InvariantCulture, $"The focal-offset series (Sweep panel, Focal series) counts from the same 0, the visible focus at Z {z.FocusMm:0.###} mm: the camera sees the sample sharpest at {peak:+0.#;-0.#;0} µm on that scale, so the series' best offset f lies f {(peak >= 0 ? "-" : "+")} {Math.Abs(peak):0.#} µm from where the camera is sharp"),
                ];
            }
        }
        catch (Exception ex) when (ex is not OperationCanceledException)
        {
            Error = ex.Message;
        }

        _shown = null;
        Refresh();
    }

    /// <summary>Laser off, Z to the sharpest offset the last sweep found.</summary>
    [RelayCommand(CanExecute = nameof(CanGoToSharpestFocus))]
    private async Task GoToSharpestFocusAsync(CancellationToken cancellationToken)
    {
        Error = null;
        if (SharpestFocusUm is not { } offset)
        {
            return;
        }

        try
        {
            await _camera.MoveFocusAsync(offset, cancellationToken);
            LastGoTo = string.Create(CultureInfo.InvariantCulture, $"Z at {offset:+0.#;-0.#;0} µm from the visible focus, the sharpest the sweep found, laser off");
        }
        catch (CameraException ex)
        {
            Error = ex.Message;
        }

        _shown = null;
        Refresh();
    }

    // The sweep's steps as they come, shown at once (not posted to a context: the panel re-renders on the change).
    private sealed class Steps(CameraViewModel owner) : IProgress<FocusPoint>
    {
        public void Report(FocusPoint value) => owner.FocusPoints = [.. owner.FocusPoints, value];
    }

    /// <summary>The page measured the live frame's sharpness (same figure as <see cref="FocusMeasure"/>).</summary>
    public void ReportLiveSharpness(double sharpness) => Sharpness = sharpness;

    /// <summary>Click to go: camera pixel (<paramref name="pixel"/>) under the spot, laser off.</summary>
    [RelayCommand(CanExecute = nameof(CanGo))]
    private async Task GoToPixelAsync((double X, double Y) pixel)
    {
        Error = null;
        if (InForce is not { } calibration || _camera.StagePositionUm is not { } stage)
        {
            return;
        }

        var (x, y) = calibration.StageTargetUm(stage.XUm, stage.YUm, pixel.X, pixel.Y);
        LastGoTo = string.Create(CultureInfo.InvariantCulture, $"Going to {Units.UmToMm(x):0.####}, {Units.UmToMm(y):0.####} mm (pixel {pixel.X:0}, {pixel.Y:0}), laser off");
        try
        {
            await _camera.GoToAsync(x, y, CancellationToken.None);
        }
        catch (CameraException ex)
        {
            Error = ex.Message;
        }
    }

    /// <summary>The alignment mark the next click picks (1 or 2); null: a click goes there.</summary>
    [ObservableProperty]
    public partial int? PickingMark { get; set; }

    /// <summary>About how wide the marks are on the sample, µm: the click snaps to the dark mark's centre within it.</summary>
    [ObservableProperty]
    public partial double MarkDiameterUm { get; set; } = 50;

    /// <summary>What the last picked mark became, one line.</summary>
    [ObservableProperty]
    public partial string? MarkText { get; private set; }

    public bool CanPickMark => _takeMark is not null && HasCamera && _camera.StagePositionUm is not null && (IsTwin || _camera.LiveCameraReady) && _camera.CanMove;

    /// <summary>A click while picking a mark: snapped to the mark's centre, its stage position given to the alignment as mark <see cref="PickingMark"/>.</summary>
    [RelayCommand(CanExecute = nameof(CanPickMark))]
    private async Task PickMarkAsync((double X, double Y) pixel)
    {
        Error = null;
        if (PickingMark is not { } mark || _takeMark is null)
        {
            return;
        }

        if (!(MarkDiameterUm > 0 && MarkDiameterUm <= 5000))
        {
            Error = string.Create(CultureInfo.InvariantCulture, $"a mark {MarkDiameterUm} µm wide must be above 0 and at most 5000 µm");
            return;
        }

        try
        {
            var (x, y, xPx, yPx) = await _camera.PickMarkAsync(pixel.X, pixel.Y, MarkDiameterUm, CancellationToken.None);
            _takeMark(mark, Units.UmToMm(x), Units.UmToMm(y));
            MarkText = string.Create(CultureInfo.InvariantCulture, $"Mark {mark}: stage {Units.UmToMm(x):0.####}, {Units.UmToMm(y):0.####} mm (clicked at pixel {pixel.X:0}, {pixel.Y:0}, snapped to the mark's centre at {xPx:0.#}, {yPx:0.#}); given to the alignment to two marks");
            PickingMark = null;
        }
        catch (CameraException ex)
        {
            Error = ex.Message;
        }
    }

    /// <summary>The next click picks mark <paramref name="mark"/> (1 or 2); pressed again, clicks go to the point again.</summary>
    public void TogglePickMark(int mark) => PickingMark = PickingMark == mark ? null : mark;

    /// <summary>The map's side, mm: a square of stage positions centred where the stage stands.</summary>
    [ObservableProperty]
    public partial double MapSizeMm { get; set; } = 1;

    /// <summary>The latest stitched map as a PNG data URL; null before one is scanned.</summary>
    [ObservableProperty]
    public partial string? MapUrl { get; private set; }

    /// <summary>What the latest map covers, stage mm: its top-left edge and its size (the stage canvas draws it there).</summary>
    [ObservableProperty]
    public partial (double XMm, double YMm, double WidthMm, double HeightMm)? MapBoxMm { get; private set; }

    /// <summary>One line about the latest map: frames, the worst seam and its scale.</summary>
    [ObservableProperty]
    public partial string? MapText { get; private set; }

    /// <summary>Why Map cannot run now; null when it can.</summary>
    public string? MapUnavailableReason => !HasCamera ? "the machine profile has no camera section"
        : !IsTwin && !_camera.LiveCameraReady ? "the live camera is not playing yet: allow the browser to use it"
        : !_camera.CanMove || _camera.StagePositionUm is null ? "connect and home the stage first; nothing else may hold the machine"
        : !(MapSizeMm > 0 && MapSizeMm <= 20) ? string.Create(CultureInfo.InvariantCulture, $"a map of {MapSizeMm} mm must be above 0 and at most 20 mm a side")
        : null;

    public bool CanScanMap => MapUnavailableReason is null;

    partial void OnMapSizeMmChanged(double value) => ScanMapCommand.NotifyCanExecuteChanged();

    /// <summary>Scans a square of <see cref="MapSizeMm"/> centred where the stage stands and stitches it; the stage goes back.</summary>
    [RelayCommand(CanExecute = nameof(CanScanMap))]
    private async Task ScanMapAsync(CancellationToken cancellationToken)
    {
        Error = null;
        if (_camera.StagePositionUm is not { } stage)
        {
            return;
        }

        var sideUm = MapSizeMm * 1000;
        try
        {
            var map = await _camera.ScanMapAsync(stage.XUm - (sideUm / 2), stage.YUm - (sideUm / 2), sideUm, sideUm, cancellationToken);
            // Pixel (0, 0) is centred at the origin: the picture's edge is half a pixel before it.
            var half = map.UmPerPixel / 2;
            MapBoxMm = (Units.UmToMm(map.OriginXUm - half), Units.UmToMm(map.OriginYUm - half), Units.UmToMm(map.Image.Width * map.UmPerPixel), Units.UmToMm(map.Image.Height * map.UmPerPixel));
            // The box first: the stage canvas draws the picture where the box says once the picture arrives.
            MapUrl = "data:image/png;base64," + Convert.ToBase64String(map.Image.ToPng());
            MapText = string.Create(CultureInfo.InvariantCulture, $"Map: {map.Frames.Count} frames, worst seam {map.WorstSeamPx:0.##} camera px over {map.Seams.Count} seams; {map.Image.Width} x {map.Image.Height} px at {map.UmPerPixel:0.###} µm a pixel");
        }
        catch (Exception ex) when (ex is not OperationCanceledException)
        {
            // Whatever stopped it (a refused move, frames that do not overlap), the panel says so.
            Error = ex.Message;
        }
    }

    [RelayCommand(CanExecute = nameof(CanCalibrate))]
    private async Task CalibrateAsync(CancellationToken cancellationToken)
    {
        Error = null;
        try
        {
            var result = await _camera.CalibrateAsync(cancellationToken);
            var c = result.Calibration;
            CalibrationLines =
            [
                string.Create(CultureInfo.InvariantCulture, $"Scale: {c.UmPerPixel:0.####} µm a camera pixel"),
                string.Create(CultureInfo.InvariantCulture, $"Rotation: {Degrees(c.RotationDeg):0.###}° against the stage's X{(c.Mirrored ? " (mirrored)" : string.Empty)}"),
                string.Create(CultureInfo.InvariantCulture, $"Spot: pixel {c.SpotXPx:0.##}, {c.SpotYPx:0.##} (test dot darkened {result.DotDarkeningGrey:0} grey levels)"),
                string.Create(CultureInfo.InvariantCulture, $"Residual: {c.ResidualUm:0.###} µm over {result.Jogs.Count} jogs"),
            ];
        }
        catch (Exception ex) when (ex is not OperationCanceledException)
        {
            // Whatever stopped it (a refused move, a device error), the panel says so: the command runs detached from the page.
            Error = ex.Message;
        }

        _shown = null;
        Refresh();
    }

    // A turn of -0.0001° would read "-0°": rounded first, and -0 made 0.
    private static double Degrees(double value) => Math.Round(value, 3) + 0.0;

    private void RefreshSoon()
    {
        if (Interlocked.Increment(ref _refreshState) > 1)
        {
            Interlocked.Exchange(ref _refreshState, 2);
            return;
        }

        _ = Task.Run(() =>
        {
            do
            {
                Interlocked.Exchange(ref _refreshState, 1);
                try
                {
                    Refresh();
                }
                catch (Exception ex) when (ex is CameraException or InvalidOperationException or ArgumentException)
                {
                    Error = ex.Message;
                }
            }
            while (Interlocked.CompareExchange(ref _refreshState, 0, 1) != 1);
        });
    }

    /// <summary>Takes the twin's frame again when the stage, the camera or the job changed, and everything drawn over it.</summary>
    public void Refresh()
    {
        // A frame costs a render of the twin: positions are reported every 200 ms while the stage follows, mostly unchanged.
        lock (_refreshLock)
        {
            var key = (_camera.IsTwin, _camera.StagePositionUm, _camera.Camera, _camera.JobBoxUm, _camera.CanMove);
            if (Equals(key, _shown))
            {
                return;
            }

            _shown = key;
            if (_camera.IsTwin && _camera.TwinFrame() is { } frame)
            {
                TwinFrameUrl = "data:image/png;base64," + Convert.ToBase64String(frame.ToPng());
                Sharpness = FocusMeasure.Sharpness(frame);
            }
            else
            {
                TwinFrameUrl = null;
            }
        }

        OnPropertyChanged(string.Empty);
        GoToPixelCommand.NotifyCanExecuteChanged();
        CalibrateCommand.NotifyCanExecuteChanged();
        ScanMapCommand.NotifyCanExecuteChanged();
        FindFocusCommand.NotifyCanExecuteChanged();
        GoToSharpestFocusCommand.NotifyCanExecuteChanged();
        PickMarkCommand.NotifyCanExecuteChanged();
    }
}
