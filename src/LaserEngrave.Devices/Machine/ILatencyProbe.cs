namespace LaserEngrave.Devices.Machine;

/// <summary>Measures the round trips to both axes and the gate (<see cref="LatencyProbe"/> on the machine's links); the seam tests fake.</summary>
public interface ILatencyProbe
{
    /// <summary>Measures <paramref name="exchanges"/> round trips to each axis and to the gate.</summary>
    Task<LatencyMeasurement> MeasureAsync(int exchanges, CancellationToken cancellationToken);
}
