using System.ComponentModel;
using System.Globalization;
using LaserEngrave.App.ViewModels;
using LaserEngrave.Core.Camera;
using LaserEngrave.Core.Geometry;
using LaserEngrave.Devices.Execution;
using LaserEngrave.Simulator.Burn;
using LaserEngrave.Simulator.Camera;

namespace LaserEngrave.App.Services;

/// <summary>The camera panel's machine: the workspace's connection and test moves, the twin's camera on the simulator.</summary>
/// <remarks>
/// A live camera runs in the page (getUserMedia); the page sends a grey frame when the server asks for one
/// (<see cref="SubmitLiveFrame"/>, checked here: size, length, rate), so calibration, marks, the focus sweep and the map
/// measure a real camera's frames as they measure the twin's.
/// </remarks>
public sealed class CameraService : ICameraService
{
    /// <summary>The largest live frame the page sends, pixels a side; a bigger camera is sent shrunk by a whole factor.</summary>
    public const int MaxLiveWidthPx = 640;

    /// <inheritdoc cref="MaxLiveWidthPx"/>
    public const int MaxLiveHeightPx = 480;

    /// <summary>Live frames closer together than this are refused: the page sends on request, a flood is a fault.</summary>
    public static readonly TimeSpan MinLiveFrameInterval = TimeSpan.FromMilliseconds(100);

    /// <summary>How long a capture waits for the page's frame before saying the live camera sends none.</summary>
    public static readonly TimeSpan LiveFrameTimeout = TimeSpan.FromSeconds(5);

    private readonly MainViewModel _main;
    private readonly TimeProvider _time;
    private readonly Lock _lock = new();
    private readonly Lock _liveLock = new();
    private (object Inspector, TwinCamera Camera)? _twin;
    private CameraProfile? _calibrated;
    private (IMachineConnection Connection, FocusAxis Axis)? _focus;
    private long? _lastLiveTimestamp;
    private TaskCompletionSource<CameraFrame>? _liveWaiter;

    /// <param name="time">The clock the live frames' rate is judged by (the page's frames come in wall-clock time).</param>
    public CameraService(MainViewModel main, TimeProvider? time = null)
    {
        ArgumentNullException.ThrowIfNull(main);
        _main = main;
        _time = time ?? TimeProvider.System;
        PropertyChangedEventHandler raise = (_, e) =>
        {
            if (e.PropertyName is nameof(MachineViewModel.Connection) or nameof(MachineViewModel.Profile) or nameof(MachineViewModel.XMicrosteps)
                or nameof(MachineViewModel.YMicrosteps) or nameof(MachineViewModel.IsBusy) or nameof(JobViewModel.Job) or nameof(JobViewModel.Drawing))
            {
                Changed?.Invoke(this, EventArgs.Empty);
            }
        };
        main.Machine.PropertyChanged += raise;
        main.Job.PropertyChanged += raise;
        main.Activity.PropertyChanged += (_, _) => Changed?.Invoke(this, EventArgs.Empty);
    }

    public event EventHandler? Changed;

    public event EventHandler? LiveFrameWanted;

    public bool LiveCameraReady { get; set; }

    public (int Width, int Height) LiveFrameSize
    {
        get
        {
            var (width, height) = Camera is { } camera ? (camera.WidthPx, camera.HeightPx) : (640, 480);
            var factor = Math.Max((width + MaxLiveWidthPx - 1) / MaxLiveWidthPx, (height + MaxLiveHeightPx - 1) / MaxLiveHeightPx);
            return (width / factor, height / factor);
        }
    }

    /// <summary>Frames the page sent that were refused (too soon after the last, or the wrong size).</summary>
    public int LiveFramesRefused { get; private set; }

    public string? SubmitLiveFrame(int width, int height, byte[] grey)
    {
        ArgumentNullException.ThrowIfNull(grey);
        var (expectedWidth, expectedHeight) = LiveFrameSize;
        string? refusal = null;
        TaskCompletionSource<CameraFrame>? waiter;
        lock (_liveLock)
        {
            var now = _time.GetTimestamp();
            if (width != expectedWidth || height != expectedHeight)
            {
                refusal = $"a live frame of {width} x {height} pixels is not the {expectedWidth} x {expectedHeight} the camera's profile asks for";
            }
            else if (grey.Length != width * height)
            {
                refusal = $"a live frame of {width} x {height} pixels came with {grey.Length} bytes, not {width * height}";
            }
            else if (_lastLiveTimestamp is { } last && _time.GetElapsedTime(last, now) < MinLiveFrameInterval)
            {
                refusal = $"live frames came faster than one every {MinLiveFrameInterval.TotalMilliseconds:0} ms; this one was dropped";
            }

            if (refusal is not null)
            {
                LiveFramesRefused++;
                return refusal;
            }

            _lastLiveTimestamp = now;
            waiter = _liveWaiter;
            _liveWaiter = null;
        }

        waiter?.TrySetResult(Enlarge(new CameraFrame(width, height, (byte[])grey.Clone())));
        return null;
    }

    public ZAxisProfile? FocusAxis => (_main.Machine.Connection?.Profile ?? _main.Machine.Profile).Z;

    public async Task<FocusSweepResult> FindFocusAsync(double fromUm, double toUm, double stepUm, IProgress<FocusPoint>? progress, CancellationToken cancellationToken)
    {
        if (FocusAxis is null)
        {
            throw new CameraException("a focus sweep needs a focus (Z) axis, and the machine profile has none");
        }

        RequireFrames("a focus sweep");
        var rig = new Rig(this);
        // Where Z stands now, to go back there; on an axis not homed yet it is not known, and Z stays at the sharpest step
        // (after a failure part way, at the visible focus: somewhere inside its limits).
        var start = await ReadFocusOffsetAsync();
        rig.FocusOffsetUm = start ?? 0;
        return await new FocusSweep(rig).RunAsync(fromUm, toUm, stepUm, cancellationToken, progress, returnToStart: start is not null);
    }

    public async Task MoveFocusAsync(double offsetUm, CancellationToken cancellationToken)
    {
        var machine = _main.Machine;
        var connection = machine.Connection ?? throw new CameraException("not connected: connect to the simulator or the machine first");
        var z = connection.Profile.Z ?? throw new CameraException("the machine profile has no focus (Z) axis");
        if (z.OffsetProblem(offsetUm) is { } problem)
        {
            throw new CameraException(string.Create(CultureInfo.InvariantCulture, $"a focus offset of {offsetUm:0.#} µm {problem}"));
        }

        var doing = string.Create(CultureInfo.InvariantCulture, $"Moving Z to {offsetUm:+0.#;-0.#;0} µm from the visible focus, laser off…");
        var ran = await machine.Guard(MachineOperation.TestMove("focus", doing), async token =>
        {
            FocusAxis axis;
            lock (_lock)
            {
                if (_focus is not { } focus || !ReferenceEquals(focus.Connection, connection))
                {
                    _focus = focus = (connection, new FocusAxis(connection.Stage, connection.Gate, connection.Profile));
                }

                axis = focus.Axis;
            }

            await axis.MoveToAsync(z.MicrostepsAt(offsetUm), token);
        });
        if (!ran || machine.Error is not null)
        {
            throw new CameraException(machine.Error ?? "the machine is busy");
        }
    }

    // Z's offset from the visible focus as the axis reports it; null when Z is not homed (its position means nothing yet) or out of its limits.
    private async Task<double?> ReadFocusOffsetAsync()
    {
        var machine = _main.Machine;
        var connection = machine.Connection ?? throw new CameraException("not connected: connect to the simulator or the machine first");
        if (connection.Profile.Z is not { } z || connection.Stage.Z is not { } axis)
        {
            throw new CameraException("the machine profile has a Z axis but the stage offers none");
        }

        double? offset = null;
        var ran = await machine.Guard(MachineOperation.TestMove("focus", "Reading Z…"), async token =>
        {
            var identity = await axis.IdentifyAsync(token);
            if (identity.IsHomed)
            {
                var um = await axis.GetPositionAsync(token) * z.MicrostepUm;
                offset = um - Units.MmToUm(z.FocusMm);
            }
        });
        if (!ran || machine.Error is not null)
        {
            throw new CameraException(machine.Error ?? "the machine is busy");
        }

        return offset is { } value && z.OffsetProblem(value) is null ? value : null;
    }

    public async Task<(double XUm, double YUm, double XPx, double YPx)> PickMarkAsync(double xPx, double yPx, double markDiameterUm, CancellationToken cancellationToken)
    {
        RequireFrames("picking a mark");
        var rig = new Rig(this);
        var navigator = new CameraNavigator(rig, Camera!.InForce);
        // The frame and the position together: the stage stands still while nothing else holds the machine.
        var position = rig.Position;
        var frame = await CaptureAsync(cancellationToken);
        if (rig.Position != position)
        {
            throw new CameraException("the stage moved while the frame was taken: pick the mark again when it stands still");
        }

        return navigator.PickMark(frame, xPx, yPx, markDiameterUm);
    }

    /// <summary>The frame to measure: the twin's, or the next one the page sends after this call.</summary>
    public async Task<CameraFrame> CaptureAsync(CancellationToken cancellationToken)
    {
        if (IsTwin)
        {
            return TwinFrame() ?? throw new CameraException("the twin's camera is gone: the simulator was disconnected");
        }

        var waiter = new TaskCompletionSource<CameraFrame>(TaskCreationOptions.RunContinuationsAsynchronously);
        lock (_liveLock)
        {
            _liveWaiter?.TrySetCanceled(CancellationToken.None);
            _liveWaiter = waiter;
        }

        // The page answers with a frame taken after this request (it waits for the camera's next frames): the stage is at rest by now.
        LiveFrameWanted?.Invoke(this, EventArgs.Empty);
        try
        {
            return await waiter.Task.WaitAsync(LiveFrameTimeout, _time, cancellationToken);
        }
        catch (TimeoutException)
        {
            throw new CameraException($"no frame came from the live camera within {LiveFrameTimeout.TotalSeconds:0} s: keep the Camera panel open in the page, with the camera allowed");
        }
        finally
        {
            lock (_liveLock)
            {
                if (_liveWaiter == waiter)
                {
                    _liveWaiter = null;
                }
            }
        }
    }

    // A frame the page shrank by a whole factor, enlarged back to the profile's pixels (bilinear), so every figure is in camera pixels.
    private CameraFrame Enlarge(CameraFrame frame)
    {
        if (Camera is not { } camera || (frame.Width == camera.WidthPx && frame.Height == camera.HeightPx))
        {
            return frame;
        }

        var small = GreyImage.Of(frame);
        var (width, height) = (camera.WidthPx, camera.HeightPx);
        var sx = (double)frame.Width / width;
        var sy = (double)frame.Height / height;
        var pixels = new byte[width * height];
        for (var y = 0; y < height; y++)
        {
            var fy = Math.Clamp(((y + 0.5) * sy) - 0.5, 0, frame.Height - 1);
            for (var x = 0; x < width; x++)
            {
                var fx = Math.Clamp(((x + 0.5) * sx) - 0.5, 0, frame.Width - 1);
                pixels[(y * width) + x] = (byte)Math.Clamp(Math.Round(small.Sample(fx, fy)), 0, 255);
            }
        }

        return new CameraFrame(width, height, pixels);
    }

    // Frames come from the twin, or from a live camera the page has opened.
    private void RequireFrames(string what)
    {
        if (Camera is null)
        {
            throw new CameraException($"{what} needs a camera: the machine profile has no camera section (docs/camera.md)");
        }

        if (!IsTwin && !LiveCameraReady)
        {
            throw new CameraException($"{what} needs the camera's frames: open the Camera panel and allow the browser to use the camera");
        }
    }

    public CameraProfile? Camera => _calibrated ?? _main.Machine.Profile.Camera ?? (IsTwin ? new CameraProfile() : null);

    public bool IsTwin => _main.Machine.Connection?.Inspector is BurnInspector;

    public (double XUm, double YUm)? StagePositionUm
    {
        get
        {
            var machine = _main.Machine;
            var profile = machine.Profile;
            return machine.XMicrosteps is { } x && machine.YMicrosteps is { } y ? (x * profile.X.MicrostepUm, y * profile.Y.MicrostepUm) : null;
        }
    }

    public (double Left, double Top, double Right, double Bottom)? JobBoxUm
    {
        get
        {
            var profile = _main.Machine.Profile;
            return _main.Job.Engraving?.FrameBox is { } box
                ? (box.Left * profile.X.MicrostepUm, box.Top * profile.Y.MicrostepUm, box.Right * profile.X.MicrostepUm, box.Bottom * profile.Y.MicrostepUm)
                : null;
        }
    }

    public bool CanMove => _main.TestMoves.CanMove;

    public CameraFrame? TwinFrame()
    {
        if (_main.Machine.Connection?.Inspector is not BurnInspector inspector || Camera is not { } optics)
        {
            return null;
        }

        lock (_lock)
        {
            if (_twin is not { } twin || !ReferenceEquals(twin.Inspector, inspector))
            {
                _twin = twin = (inspector, new TwinCamera(inspector.Machine, optics: optics));
            }

            return twin.Camera.Capture();
        }
    }

    public async Task GoToAsync(double xUm, double yUm, CancellationToken cancellationToken)
    {
        var moves = _main.TestMoves;
        moves.GoToXMm = Units.UmToMm(xUm);
        moves.GoToYMm = Units.UmToMm(yUm);
        await moves.GoToCommand.ExecuteAsync(null);
        if (moves.Error is { } error)
        {
            throw new CameraException(error);
        }
    }

    public async Task<CameraCalibrationResult> CalibrateAsync(CancellationToken cancellationToken)
    {
        RequireFrames("calibrating");
        var camera = Camera!;
        var result = await new CameraCalibrator(new Rig(this)).CalibrateAsync(camera.InForce, fireDot: true, cancellationToken);
        _calibrated = camera with { Calibration = result.Calibration };
        Changed?.Invoke(this, EventArgs.Empty);
        return result;
    }

    public async Task<SampleMap> ScanMapAsync(double x0Um, double y0Um, double widthUm, double heightUm, CancellationToken cancellationToken)
    {
        RequireFrames("a map");
        var camera = Camera!;
        var rig = new Rig(this);
        var (startX, startY) = rig.Position;
        // Two camera pixels a map pixel: a few megapixels at most for a map of some millimetres, and seams still measured in full frames.
        var umPerPixel = Math.Round(2 * camera.InForce.UmPerPixel, 3);
        try
        {
            return await new MapStitcher(rig, camera.InForce).ScanAsync(x0Um, y0Um, widthUm, heightUm, umPerPixel, cancellationToken);
        }
        finally
        {
            await GoToAsync(startX, startY, CancellationToken.None);
        }
    }

    // The camera features' rig over the workspace: moves and the dot through the test moves (laser off between), Z through
    // the focus axis (laser off first), frames from the twin or the live camera.
    private sealed class Rig(CameraService service) : ICameraRig
    {
        public (double XUm, double YUm) Position => service.StagePositionUm ?? throw new CameraException("the stage's position is not known: connect and home first");

        public bool HasFocusAxis => service.FocusAxis is not null;

        public double FocusOffsetUm { get; set; }

        public Task MoveToAsync(double xUm, double yUm, CancellationToken cancellationToken) => service.GoToAsync(xUm, yUm, cancellationToken);

        public async Task MoveFocusAsync(double offsetUm, CancellationToken cancellationToken)
        {
            await service.MoveFocusAsync(offsetUm, cancellationToken);
            FocusOffsetUm = offsetUm;
        }

        public Task<CameraFrame> CaptureAsync(CancellationToken cancellationToken) => service.CaptureAsync(cancellationToken);

        public async Task FireDotAsync(CancellationToken cancellationToken)
        {
            var moves = service._main.TestMoves;
            moves.TestFirePulses = 20;
            await moves.TestFireCommand.ExecuteAsync(null);
            if (moves.Error is { } error)
            {
                throw new CameraException(error);
            }
        }
    }
}
