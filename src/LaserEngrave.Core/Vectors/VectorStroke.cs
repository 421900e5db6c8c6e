namespace LaserEngrave.Core.Vectors;

/// <summary>
/// One stroke of a vector job: the axes from rest at <see cref="RunUpStart"/> along a run-up, the burned path at the
/// burn speed, a run-out and rest again; every command timed from the stroke's origin (its first command's arrival).
/// </summary>
public sealed record VectorStroke
{
    /// <summary>The stroke's place in the job, 0-based (a resumed run starts at a stroke).</summary>
    public required int Index { get; init; }

    /// <summary>The index in <see cref="VectorPlan.Paths"/> of the path this stroke burns (all or part of).</summary>
    public required int PathIndex { get; init; }

    /// <summary>The path burned, from its first vertex to its last (a part of a drawing's path when a corner splits it).</summary>
    public required StagePath Path { get; init; }

    /// <summary>Where both axes stand before the stroke: the run-up's start, on the first segment's line extended backwards.</summary>
    public required StagePoint RunUpStart { get; init; }

    /// <summary>Where the model says the axes come to rest after the run-out, rounded.</summary>
    public required StagePoint RestEnd { get; init; }

    /// <summary>Every axis command in time order.</summary>
    public required IReadOnlyList<AxisCommand> Commands { get; init; }

    /// <summary>
    /// Whether the stroke streams <paramref name="axis"/>' speed: where that axis then rests depends on when each command
    /// arrived (the latencies' spread), so <see cref="RestEnd"/> is the model's, not a position to start the next stroke from.
    /// </summary>
    public bool Streams(VectorAxis axis) => Commands.Any(c => c.Axis == axis && c.Kind != AxisCommandKind.Query);

    /// <summary>The position the query (<see cref="AxisCommandKind.Query"/>) should see, microsteps.</summary>
    public required long QueryExpected { get; init; }

    /// <summary>The laser's switch-on takes effect now (a pulse half period, or the latencies' guard, after the path's start).</summary>
    public required double LaserOnSeconds { get; init; }

    /// <summary>The laser's switch-off takes effect now (the latencies' guard before the path's end).</summary>
    public required double LaserOffSeconds { get; init; }

    /// <summary>When both axes rest after the run-out.</summary>
    public required double RestSeconds { get; init; }

    /// <summary>The earliest arrival of the travel to the next stroke: at rest, and the switch-off acknowledged.</summary>
    public required double NextArrivalSeconds { get; init; }

    /// <summary>The model's largest distance from the path while the laser is on, µm.</summary>
    public required double PredictedDeviationUm { get; init; }
}
