namespace LaserEngrave.Core.Camera;

/// <summary>What the camera features need of a machine: the stage's place, moves with the laser off, a frame, a test dot, the focus axis.</summary>
/// <remarks>
/// Positions are the stage's, µm from home, as whole microsteps reached (the rig rounds once). Every move leaves the
/// laser off; only <see cref="FireDotAsync"/> fires, at the spot where the stage stands.
/// </remarks>
public interface ICameraRig
{
    /// <summary>Where the stage stands, µm.</summary>
    (double XUm, double YUm) Position { get; }

    /// <summary>Whether the machine has a focus (Z) axis.</summary>
    bool HasFocusAxis { get; }

    /// <summary>The focus offset in force, µm from the profile's visible focus; 0 without a Z axis.</summary>
    double FocusOffsetUm { get; }

    /// <summary>Laser off, then the stage to (<paramref name="xUm"/>, <paramref name="yUm"/>), awaited.</summary>
    Task MoveToAsync(double xUm, double yUm, CancellationToken cancellationToken);

    /// <summary>Laser off, then Z to the focus offset <paramref name="offsetUm"/> µm, awaited.</summary>
    Task MoveFocusAsync(double offsetUm, CancellationToken cancellationToken);

    /// <summary>The next camera frame taken after the stage came to rest.</summary>
    Task<CameraFrame> CaptureAsync(CancellationToken cancellationToken);

    /// <summary>One test dot where the stage stands (a short burst), laser off after it.</summary>
    Task FireDotAsync(CancellationToken cancellationToken);
}
