using System.ComponentModel;
using LaserEngrave.App.ViewModels;
using LaserEngrave.Core.Camera;
using LaserEngrave.Core.Geometry;
using LaserEngrave.Simulator.Burn;
using LaserEngrave.Simulator.Camera;

namespace LaserEngrave.App.Services;

/// <summary>The camera panel's machine: the workspace's connection and test moves, the twin's camera on the simulator.</summary>
/// <remarks>
/// A live camera's frames stay in the page (getUserMedia); the server sees only the twin's. So calibration, which needs
/// frames here, runs on the twin; with a live camera the panel says so instead of measuring.
/// </remarks>
public sealed class CameraService : ICameraService
{
    private readonly MainViewModel _main;
    private readonly Lock _lock = new();
    private (object Inspector, TwinCamera Camera)? _twin;
    private CameraProfile? _calibrated;

    public CameraService(MainViewModel main)
    {
        ArgumentNullException.ThrowIfNull(main);
        _main = main;
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
        if (!IsTwin || Camera is not { } camera)
        {
            throw new CameraException("calibrating needs the camera's frames in the app, which it has only on the simulator so far: connect to the simulator, or enter the figures in the profile's camera section (docs/camera.md)");
        }

        var result = await new CameraCalibrator(new Rig(this)).CalibrateAsync(camera.InForce, fireDot: true, cancellationToken);
        _calibrated = camera with { Calibration = result.Calibration };
        Changed?.Invoke(this, EventArgs.Empty);
        return result;
    }

    public async Task<SampleMap> ScanMapAsync(double x0Um, double y0Um, double widthUm, double heightUm, CancellationToken cancellationToken)
    {
        if (!IsTwin || Camera is not { } camera)
        {
            throw new CameraException("a map needs the camera's frames in the app, which it has only on the simulator so far: connect to the simulator");
        }

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

    // The calibration's rig over the workspace: moves and the dot through the test moves (laser off between), frames from the twin.
    private sealed class Rig(CameraService service) : ICameraRig
    {
        public (double XUm, double YUm) Position => service.StagePositionUm ?? throw new CameraException("the stage's position is not known: connect and home first");

        public bool HasFocusAxis => false;

        public double FocusOffsetUm => 0;

        public Task MoveToAsync(double xUm, double yUm, CancellationToken cancellationToken) => service.GoToAsync(xUm, yUm, cancellationToken);

        public Task MoveFocusAsync(double offsetUm, CancellationToken cancellationToken) =>
            throw new CameraException("the camera panel does not move Z yet");

        public Task<CameraFrame> CaptureAsync(CancellationToken cancellationToken) =>
            Task.FromResult(service.TwinFrame() ?? throw new CameraException("the twin's camera is gone: the simulator was disconnected"));

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
