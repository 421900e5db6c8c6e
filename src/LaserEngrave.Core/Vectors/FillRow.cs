namespace LaserEngrave.Core.Vectors;

/// <summary>One scan line of a fill: where it runs and the burn segments along it, left to right, like a raster row's burn runs.</summary>
/// <param name="Y">Stage Y of the scan line, microsteps.</param>
/// <param name="Segments">Burn segments [X0, X1] in microsteps, X0 &lt; X1, left to right, not overlapping.</param>
public sealed record FillRow(long Y, IReadOnlyList<(long X0, long X1)> Segments);
