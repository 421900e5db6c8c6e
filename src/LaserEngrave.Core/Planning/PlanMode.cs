namespace LaserEngrave.Core.Planning;

/// <summary>How the laser meets the material: burning while the stage moves, or standing at each dot and firing a counted burst.</summary>
public enum PlanMode
{
    /// <summary>The laser fires at its frequency while the stage moves along a run (seed 000).</summary>
    Raster,

    /// <summary>The stage stops at each dot and the gate fires exactly <see cref="ProcessSettings.PulsesPerDot"/> pulses (seed 004's N pulses per dot). docs/process.md.</summary>
    Dots,
}
