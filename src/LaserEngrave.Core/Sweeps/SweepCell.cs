using LaserEngrave.Core.Jobs;

namespace LaserEngrave.Core.Sweeps;

/// <summary>One cell of a sweep: where it is in the grid and on the stage, the values it was given, and its job.</summary>
/// <param name="Row">Grid row, from 0.</param>
/// <param name="Column">Grid column, from 0.</param>
/// <param name="Parameters">The swept values of this cell, by <see cref="SweepParameters.LogKey"/> (e.g. speedMmPerS = 0.5).</param>
/// <param name="Job">The cell's job: its mask, geometry, process and passes.</param>
public sealed record SweepCell(int Row, int Column, IReadOnlyDictionary<string, double> Parameters, PreparedJob Job)
{
    /// <summary>The absolute Z position the cell is burned at, whole microsteps (<see cref="Geometry.ZAxisProfile.MicrostepsAt"/>); null when the sweep does not vary the focus.</summary>
    public long? FocusZMicrosteps { get; init; }

    /// <summary>The cell's top-left corner on the stage, mm.</summary>
    public double OriginXMm => Job.Spec.Origin.X;

    public double OriginYMm => Job.Spec.Origin.Y;

    /// <summary>What the cell is called in messages: "row 2, column 3 (speed 4 mm/s, frequency 1000 Hz)".</summary>
    public string Describe() => Describe(Row, Column, Parameters);

    /// <inheritdoc cref="Describe()"/>
    public static string Describe(int row, int column, IReadOnlyDictionary<string, double> parameters) =>
        $"cell row {row + 1}, column {column + 1} ({SweepParameters.Describe(parameters)})";
}
