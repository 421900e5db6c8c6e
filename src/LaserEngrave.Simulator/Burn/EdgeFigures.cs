namespace LaserEngrave.Simulator.Burn;

/// <summary>How far the first and last pulse of every burn run land from where the pixel edges say they should.</summary>
/// <remarks>
/// The first pulse of a run is exact half a pulse spacing inside the run's left pixel edge, the last half a spacing inside
/// its right edge (the spacing being burn speed / frequency); the error of an end is the distance along the row between
/// the outermost pulse's centre and that point, whichever way the run was burned.
/// </remarks>
/// <param name="Count">Run ends measured: two for every burn run of the expected image that received a pulse.</param>
/// <param name="MeanErrorUm">Mean of the ends' errors, µm (0 without ends).</param>
/// <param name="MaxErrorUm">Largest end error, µm (0 without ends).</param>
/// <param name="MissingRuns">Burn runs of the expected image that received no pulse at all (not counted as edge errors).</param>
public sealed record EdgeFigures(int Count, double MeanErrorUm, double MaxErrorUm, int MissingRuns);
