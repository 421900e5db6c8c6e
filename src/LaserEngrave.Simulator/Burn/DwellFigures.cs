namespace LaserEngrave.Simulator.Burn;

/// <summary>Pulses fired while the stage stood still or crawled: each lands on (nearly) the same spot as the one before.</summary>
/// <param name="Count">Maximal stretches of consecutive dwell pulses within one laser-on period.</param>
/// <param name="Pulses">Dwell pulses in all: fired while the stage's speed along its path was under a tenth of the burn speed.</param>
public sealed record DwellFigures(int Count, long Pulses);
