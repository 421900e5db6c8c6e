namespace LaserEngrave.Simulator.Burn;

/// <summary>Pulses landed per pixel, over the pixels the expected image has black (over the burned pixels without one).</summary>
/// <param name="Min">Fewest pulses on one such pixel (0 when one was missed).</param>
/// <param name="Mean">Mean pulses per such pixel.</param>
/// <param name="Max">Most pulses on one such pixel.</param>
public sealed record PulsesPerPixelFigures(int Min, double Mean, int Max);
