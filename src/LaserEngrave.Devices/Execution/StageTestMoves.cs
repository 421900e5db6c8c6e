using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Planning;
using LaserEngrave.Devices.Abstractions;

namespace LaserEngrave.Devices.Execution;

/// <summary>An axis of the stage, for jogging.</summary>
public enum StageAxisName
{
    X,
    Y,
}

/// <summary>A stage position in whole microsteps.</summary>
public readonly record struct StagePosition(long XMicrosteps, long YMicrosteps);

/// <summary>A test move whose target is unusable (outside the travel, not a number); the message is one line.</summary>
public sealed class TestMoveException : DeviceException
{
    public TestMoveException(string message)
        : base(message)
    {
    }
}

/// <summary>Moves a technician makes before or between runs: jog, go to, home, frame the job, test fire; the laser is always off at the end.</summary>
/// <remarks>
/// Moves run at the process' travel speed and acceleration (set before each operation). Targets are checked against
/// the profile's travel before anything is sent. Waits run on the given <see cref="TimeProvider"/>.
/// </remarks>
public sealed class StageTestMoves
{
    public StageTestMoves(IStage stage, ILaserGate gate, MachineProfile profile, ProcessSettings? process = null, TimeProvider? timeProvider = null)
    {
        ArgumentNullException.ThrowIfNull(stage);
        ArgumentNullException.ThrowIfNull(gate);
        ArgumentNullException.ThrowIfNull(profile);
        Stage = stage;
        Gate = gate;
        Profile = profile;
        Process = process ?? ProcessSettings.FromProfile(profile);
        TimeProvider = timeProvider ?? TimeProvider.System;
    }

    public IStage Stage { get; }

    public ILaserGate Gate { get; }

    public MachineProfile Profile { get; }

    public ProcessSettings Process { get; }

    public TimeProvider TimeProvider { get; }

    /// <summary>Reads both axes' positions.</summary>
    public Task<StagePosition> GetPositionAsync(CancellationToken cancellationToken) => throw new NotImplementedException();

    /// <summary>Moves one axis by <paramref name="stepUm"/> µm (signed), laser off.</summary>
    /// <exception cref="TestMoveException">The target lies outside the travel.</exception>
    public Task<StagePosition> JogAsync(StageAxisName axis, double stepUm, CancellationToken cancellationToken) => throw new NotImplementedException();

    /// <summary>Moves to (<paramref name="xMm"/>, <paramref name="yMm"/>) mm, laser off.</summary>
    /// <exception cref="TestMoveException">The target lies outside the travel.</exception>
    public Task<StagePosition> GoToAsync(double xMm, double yMm, CancellationToken cancellationToken) => throw new NotImplementedException();

    /// <summary>Moves to the job's origin (the top-left corner of the image on the stage), laser off.</summary>
    public Task<StagePosition> GoToOriginAsync(JobGeometry geometry, CancellationToken cancellationToken) => throw new NotImplementedException();

    /// <summary>Homes both axes, laser off.</summary>
    public Task<StagePosition> HomeAsync(CancellationToken cancellationToken) => throw new NotImplementedException();

    /// <summary>Traces the job's bounding rectangle (top-left, top-right, bottom-right, bottom-left, back), laser off,
    /// or at <paramref name="visibleFrequencyHz"/> to see it; ends at the top-left corner with the laser off.</summary>
    /// <exception cref="TestMoveException">The rectangle lies outside the travel, or the frequency is not above 0.</exception>
    public Task<StagePosition> FrameAsync(JobGeometry geometry, int? visibleFrequencyHz, CancellationToken cancellationToken) => throw new NotImplementedException();

    /// <summary>Fires <paramref name="pulses"/> pulses at <paramref name="frequencyHz"/> at the current position (the gate's burst), then off.</summary>
    public Task FirePulsesAsync(int pulses, int frequencyHz, CancellationToken cancellationToken) => throw new NotImplementedException();

    /// <summary>Fires at <paramref name="frequencyHz"/> for <paramref name="duration"/> at the current position, then off.</summary>
    public Task FireForAsync(TimeSpan duration, int frequencyHz, CancellationToken cancellationToken) => throw new NotImplementedException();
}
