using LaserEngrave.Core.Camera;
using LaserEngrave.Core.Geometry;
using LaserEngrave.Devices.Execution;
using LaserEngrave.Devices.Machine;
using LaserEngrave.Simulator.Camera;

namespace LaserEngrave.Simulator.Tests.Camera;

/// <summary>The camera features' rig through the wire: moves, Z and the test dot as the host sends them (Zaber binary and the gate's lines over the twin's links), frames from the twin's camera.</summary>
/// <remarks>
/// Unlike <see cref="TwinCameraRig"/>, which places the axes directly, every move here is the host's <see cref="StageTestMoves"/>
/// over a <see cref="MachineSession"/> on the twin's links, awaited to the devices' replies, and the position is what the
/// stage replied; the test dot is a real burst of the gate, burned by the twin. So the figures include what the wire adds.
/// </remarks>
internal sealed class WireCameraRig : ICameraRig, IAsyncDisposable
{
    private readonly MachineSession _session;
    private readonly StageTestMoves _moves;
    private readonly FocusAxis? _focus;
    private StagePosition _position;

    private WireCameraRig(SimulatedMachine machine, TwinCamera camera, MachineSession session)
    {
        Machine = machine;
        Camera = camera;
        _session = session;
        _moves = new StageTestMoves(session.Stage, session.Gate, machine.Profile, timeProvider: session.TimeProvider);
        _focus = machine.Profile.Z is null ? null : new FocusAxis(session.Stage, session.Gate, machine.Profile);
    }

    public SimulatedMachine Machine { get; }

    public TwinCamera Camera { get; }

    /// <summary>Moves sent over the wire so far.</summary>
    public int Moves { get; private set; }

    public (double XUm, double YUm) Position => (_position.XMicrosteps * Machine.Profile.X.MicrostepUm, _position.YMicrosteps * Machine.Profile.Y.MicrostepUm);

    public bool HasFocusAxis => _focus is not null;

    public double FocusOffsetUm { get; private set; }

    /// <summary>The twin in virtual time with the host's session on its links, the position read over the wire.</summary>
    public static async Task<WireCameraRig> OpenAsync(MachineProfile profile, TwinCameraOptions? options = null)
    {
        var machine = SimulatedMachine.CreateInProcess(profile);
        var session = MachineSession.OverLinks(machine.StageLink, machine.LaserLink, profile, machine.TimeProvider, "simulator", owner: machine);
        var rig = new WireCameraRig(machine, new TwinCamera(machine, options), session);
        rig._position = await session.RunAsync(() => rig._moves.GetPositionAsync(CancellationToken.None));
        return rig;
    }

    public async Task MoveToAsync(double xUm, double yUm, CancellationToken cancellationToken)
    {
        _position = await _session.RunAsync(() => _moves.GoToAsync(Units.UmToMm(xUm), Units.UmToMm(yUm), cancellationToken));
        Moves++;
    }

    public async Task MoveFocusAsync(double offsetUm, CancellationToken cancellationToken)
    {
        var focus = _focus ?? throw new CameraException("the machine has no focus (Z) axis");
        var z = Machine.Profile.Z!;
        if (z.OffsetProblem(offsetUm) is { } problem)
        {
            throw new CameraException($"a focus offset of {offsetUm} µm {problem}");
        }

        await _session.RunAsync(() => focus.MoveToAsync(z.MicrostepsAt(offsetUm), cancellationToken));
        FocusOffsetUm = offsetUm;
    }

    // Taken on the simulation's loop, after the move's reply: the twin's clock stands where the host heard the stage arrive.
    public Task<CameraFrame> CaptureAsync(CancellationToken cancellationToken) => _session.RunAsync(() => Task.FromResult(Camera.Capture()));

    public Task FireDotAsync(CancellationToken cancellationToken) => _session.RunAsync(() => _moves.FirePulsesAsync(20, 1000, cancellationToken));

    public ValueTask DisposeAsync() => _session.DisposeAsync();
}
