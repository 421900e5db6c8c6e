namespace LaserEngrave.Core.Logging;

/// <summary>What the simulator (the twin) measured of a simulated run: the physics of its edges.</summary>
/// <param name="Seed">The seed of the simulation's random draws; the same seed repeats the run exactly.</param>
/// <param name="Pulses">Q-switch pulses fired.</param>
/// <param name="Edges">Distance of each burn run's first and last pulse from where its pixel edge says, half a pulse spacing inside.</param>
/// <param name="Dwells">Pulses fired with the stage still or below a tenth of the burn speed, and the stretches of them.</param>
/// <param name="PulsesPerPixel">Pulses per pixel over the pixels the mask has black.</param>
/// <param name="LaserOnTravelCount">Pulses that landed on a white pixel or off the job.</param>
/// <param name="MissingPixels">Black pixels of the mask that got no pulse.</param>
/// <param name="ExtraPixels">White pixels of the mask that got a pulse.</param>
/// <param name="PulsesWhileMoving">Pulses fired while the stage moved (null in logs written before it was measured); dot mode fires none.</param>
public sealed record RunSimulation(
    int Seed,
    long Pulses,
    EdgeErrors? Edges,
    DwellCounts? Dwells,
    PulseCountRange PulsesPerPixel,
    long LaserOnTravelCount,
    long MissingPixels,
    long ExtraPixels,
    long? PulsesWhileMoving = null)
{
    /// <summary>For a drawing: each pulse's distance from the path and the pulses' spacing along it; null for an image.</summary>
    public PathFigures? Path { get; init; }

    /// <summary>On a machine with a Z axis: where Z stood while the laser fired, and the spot that gives; null without one.</summary>
    public FocusFigures? Focus { get; init; }
}

/// <summary>The focus axis while the laser fired, as the simulator measured it.</summary>
/// <param name="ZMinMicrosteps">Lowest Z position while firing, microsteps (rounded).</param>
/// <param name="ZMaxMicrosteps">Highest, microsteps; equal to the lowest when Z stood still.</param>
/// <param name="LaserOnWhileZMoving">Laser-on periods during which Z moved: 0 when every focus move was made with the laser off.</param>
/// <param name="DefocusUm">Z's distance from the simulated true focus, µm (mean of the lowest and highest).</param>
/// <param name="SpotDiameterUm">The spot at that defocus, d0 √(1 + (Δz / zR)²); null when the simulator's Rayleigh length is not set.</param>
public sealed record FocusFigures(long ZMinMicrosteps, long ZMaxMicrosteps, int LaserOnWhileZMoving, double DefocusUm, double? SpotDiameterUm);

/// <summary>Edge placement over the burn runs: how many edges, their mean and largest error, µm.</summary>
public sealed record EdgeErrors(int Count, double MeanErrorUm, double MaxErrorUm);

/// <summary>Dwell: how many stretches, how many pulses in them.</summary>
public sealed record DwellCounts(int Count, long Pulses);

/// <summary>Smallest, mean and largest pulse count.</summary>
public sealed record PulseCountRange(int Min, double Mean, int Max);
