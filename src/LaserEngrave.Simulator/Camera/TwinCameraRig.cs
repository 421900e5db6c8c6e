using LaserEngrave.Core.Camera;
using LaserEngrave.Core.Geometry;
using LaserEngrave.Simulator.Motion;

namespace LaserEngrave.Simulator.Camera;

/// <summary>The camera features' rig on the twin without a host: moves place the twin's axes at once, a test dot is a mark of the spot's size.</summary>
/// <remarks>
/// For tests of the camera's measurements: the axes stand at whole microsteps (rounded once from µm, as the host would
/// send them), so what a measurement gets wrong is the camera's doing, not the motion's. The app on the simulator
/// moves the stage through the ordinary Zaber commands instead.
/// </remarks>
public sealed class TwinCameraRig : ICameraRig
{
    private readonly SimulatedMachine _machine;

    public TwinCameraRig(SimulatedMachine machine, TwinCamera camera)
    {
        ArgumentNullException.ThrowIfNull(machine);
        ArgumentNullException.ThrowIfNull(camera);
        _machine = machine;
        Camera = camera;
    }

    public TwinCamera Camera { get; }

    /// <summary>Moves made so far.</summary>
    public int Moves { get; private set; }

    public (double XUm, double YUm) Position => Camera.StagePositionUm();

    public bool HasFocusAxis => _machine.Profile.Z is not null;

    public double FocusOffsetUm
    {
        get
        {
            if (_machine.Profile.Z is not { } z || _machine.Recorder.Z is not { } trajectory)
            {
                return 0;
            }

            return (trajectory.PositionAt(_machine.NowSeconds) * z.MicrostepUm) - (z.FocusMm * 1000);
        }
    }

    public Task MoveToAsync(double xUm, double yUm, CancellationToken cancellationToken)
    {
        cancellationToken.ThrowIfCancellationRequested();
        var profile = _machine.Profile;
        Place(_machine.Recorder.X, profile.X, xUm);
        Place(_machine.Recorder.Y, profile.Y, yUm);
        Moves++;
        return Task.CompletedTask;
    }

    public Task MoveFocusAsync(double offsetUm, CancellationToken cancellationToken)
    {
        cancellationToken.ThrowIfCancellationRequested();
        var z = _machine.Profile.Z ?? throw new InvalidOperationException("the machine has no focus (Z) axis");
        if (z.OffsetProblem(offsetUm) is { } problem)
        {
            throw new ArgumentOutOfRangeException(nameof(offsetUm), offsetUm, $"a focus offset of {offsetUm} µm {problem}");
        }

        var now = _machine.NowSeconds;
        _machine.Recorder.Z!.Replace(now, [MotionSegment.Hold(now, z.MicrostepsAt(offsetUm))]);
        return Task.CompletedTask;
    }

    public Task<CameraFrame> CaptureAsync(CancellationToken cancellationToken)
    {
        cancellationToken.ThrowIfCancellationRequested();
        return Task.FromResult(Camera.Capture());
    }

    public Task FireDotAsync(CancellationToken cancellationToken)
    {
        cancellationToken.ThrowIfCancellationRequested();
        var (x, y) = Position;
        Camera.AddMark(x, y, _machine.Profile.SpotDiameterUm);
        return Task.CompletedTask;
    }

    private void Place(AxisTrajectory trajectory, AxisProfile axis, double um)
    {
        var microsteps = Math.Round(StageUnits.UmToMicrosteps(um, axis.MicrostepUm));
        if (microsteps < 0 || microsteps > axis.TravelMicrosteps)
        {
            throw new ArgumentOutOfRangeException(nameof(um), um, $"{um} µm is outside the axis' travel");
        }

        var now = _machine.NowSeconds;
        trajectory.Replace(now, [MotionSegment.Hold(now, microsteps)]);
    }
}
