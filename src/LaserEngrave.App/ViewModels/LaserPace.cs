using LaserEngrave.Core.Jobs;
using LaserEngrave.Core.Motion;
using LaserEngrave.Core.Planning;
using LaserEngrave.Core.Programs;
using LaserEngrave.Devices.Execution;

namespace LaserEngrave.App.ViewModels;

/// <summary>
/// Where the laser is drawn between two progress reports of a run: along the motion under way, from where the last
/// report put the stage, at its planned pace (a travel's ramps at the travel speed, a burn or overscan at the burn
/// speed). Every kind of job: a raster's plan move by move, a dot job's travel to its next dot, a drawing's travel to its
/// next stroke and the stroke itself, and each layer of a job of layers with its own process. It reads only the job and
/// the machine's clock, never the ports: a run owns them.
/// </summary>
/// <remarks>
/// The engine reports when a move (a dot, a stroke) ends; without this the cross stood still for a whole row or stroke
/// and then jumped. A stroke is drawn at the burn speed from its run-up's start (its ramps are not drawn).
/// The clock is the machine's (the engine's): the simulator's virtual time may run behind the wall clock, and a cross
/// paced by the wall clock would then run ahead of the stage it stands for. During a timed raster's stroke the engine
/// itself says where its timing puts the stage (<see cref="EngraveSession.StrokePositionAt"/>): its flown gaps at the
/// travel speed and the corrections its position queries found, which the plan's moves alone do not know.
/// </remarks>
public sealed class LaserPace
{
    private readonly IReadOnlyList<PreparedLayer> _parts;
    private readonly TimeProvider _time;
    private readonly Func<long, StrokePosition?>? _engine;

    // The engine reports on its thread and the page's timer asks on another.
    private readonly Lock _lock = new();
    private Part? _part;
    private int _layer;
    private int _pass;
    private long _movesDone = -1;
    private (long X, long Y) _from;
    private IReadOnlyList<Leg> _legs = [];
    private long _reportedAt;

    /// <param name="job">What runs.</param>
    /// <param name="time">The machine's clock: the one the engine's reports happen on.</param>
    /// <param name="engine">Where the engine's timing puts the stage at a timestamp of <paramref name="time"/> during a timed stroke (the run's <see cref="EngraveSession.StrokePositionAt"/>); null: the plan alone.</param>
    public LaserPace(EngraveJob job, TimeProvider time, Func<long, StrokePosition?>? engine = null)
    {
        ArgumentNullException.ThrowIfNull(job);
        ArgumentNullException.ThrowIfNull(time);
        _parts = job.Parts;
        _time = time;
        _engine = engine;
    }

    /// <summary>A progress report of a single job: <paramref name="movesDone"/> of the pass's moves are done and the stage stood at (x, y).</summary>
    public void Report(int pass, long movesDone, long x, long y) => Report(1, pass, movesDone, x, y);

    /// <summary>A progress report: in layer <paramref name="layer"/> (from 1), <paramref name="movesDone"/> of the pass's moves (dots, strokes) are done and the stage stood at (x, y).</summary>
    public void Report(int layer, int pass, long movesDone, long x, long y)
    {
        lock (_lock)
        {
            if (layer == _layer && pass == _pass && movesDone == _movesDone)
            {
                // The same move still in flight: its clock keeps running from when it began.
                return;
            }

            if (layer != _layer || pass != _pass || _part is null || movesDone < _movesDone)
            {
                // A new layer or pass starts its part's moves again.
                _part = layer >= 1 && layer <= _parts.Count ? new Part(_parts[layer - 1]) : null;
            }

            _layer = layer;
            _pass = pass;
            _movesDone = movesDone;
            _reportedAt = _time.GetTimestamp();
            (long X, long Y)? start = null;
            _legs = _part?.LegsAt(movesDone, out start) ?? [];

            // A raster's engine reports the stage where its row began for the whole row; the plan knows where each of
            // the row's moves starts, so the cross goes on from there rather than jumping back to the row's start.
            _from = start ?? (x, y);
        }
    }

    /// <summary>The laser now: on the motion in flight at its planned pace; where the last report put it when none is in flight or the run is not moving; null before the first report.</summary>
    public (long X, long Y)? Now(bool moving) => Now(moving, out _);

    /// <summary>The laser now, and the instant it is for: seconds on the machine's clock (its timestamp).</summary>
    public (long X, long Y)? Now(bool moving, out double atSeconds)
    {
        var now = _time.GetTimestamp();
        atSeconds = now / (double)_time.TimestampFrequency;
        var stroke = moving ? _engine?.Invoke(now) : null;
        lock (_lock)
        {
            if (_movesDone < 0)
            {
                return null;
            }

            if (!moving || _part is not { } part)
            {
                return _from;
            }

            // The engine's motion (a stroke, a travel) while the reports have not gone past the move after it: a travel is
            // counted done once its commands are sent, while the stage is still on it.
            if (stroke is { } s && _movesDone <= s.FirstMoveIndex + s.MoveCount)
            {
                return (s.X, s.Y);
            }

            var seconds = _time.GetElapsedTime(_reportedAt, now).TotalSeconds;
            var at = _from;
            foreach (var leg in _legs)
            {
                var length = Math.Max(Math.Abs(leg.X - at.X), Math.Abs(leg.Y - at.Y));
                if (length == 0)
                {
                    continue;
                }

                var profile = leg.Travel ? new TrapezoidProfile(length, part.TravelPerS, part.AccelerationPerS2) : (TrapezoidProfile?)null;
                var duration = profile?.Duration ?? length / part.BurnPerS;
                if (seconds < duration)
                {
                    var share = (profile?.DistanceAt(seconds) ?? seconds * part.BurnPerS) / length;
                    return (at.X + (long)Math.Round((leg.X - at.X) * share), at.Y + (long)Math.Round((leg.Y - at.Y) * share));
                }

                seconds -= duration;
                at = (leg.X, leg.Y);
            }

            return at;
        }
    }

    /// <summary>One straight stretch of a motion: to (X, Y), as a travel (ramps, travel speed) or at the burn speed.</summary>
    private readonly record struct Leg(bool Travel, long X, long Y);

    /// <summary>One part (a layer, or the whole single job): its speeds in X microsteps and its moves, walked forward only.</summary>
    private sealed class Part
    {
        private readonly PartProgram _program;
        private IEnumerator<Move>? _moves;
        private IEnumerator<DotStep>? _dots;
        private long _index = -1;

        public Part(PreparedLayer layer)
        {
            _program = layer.Program();

            // Speeds in X microsteps: burns run along X (or along the path), travels move both axes at once (the longer one sets the time).
            var spec = layer.Spec;
            var perMm = 1000 / spec.Profile.X.MicrostepUm;
            BurnPerS = spec.Process.BurnSpeedMmPerS * perMm;
            TravelPerS = spec.Process.TravelSpeedMmPerS * perMm;
            AccelerationPerS2 = spec.Process.AccelerationMmPerS2 * perMm;
        }

        public double BurnPerS { get; }

        public double TravelPerS { get; }

        public double AccelerationPerS2 { get; }

        /// <summary>The motion after <paramref name="done"/> moves (dots, strokes) of this part: what the engine does until it reports the next.</summary>
        /// <remarks>
        /// Read from the part's program, whose kind says what the engine counts between reports: a drawing's strokes, a
        /// dot job's dots, a raster's plan moves (those of its travels, strokes and plain moves).
        /// </remarks>
        public IReadOnlyList<Leg> LegsAt(long done, out (long X, long Y)? start)
        {
            start = null;
            switch (_program)
            {
                case DrawingProgram drawing:
                    if (done < 0 || done >= drawing.StrokeCount)
                    {
                        return [];
                    }

                    // A stroke: the travel to its run-up, then along its path to where it rests.
                    var step = drawing.Steps((int)done).First();
                    var stroke = step.Stroke;
                    return [new(true, step.Travel.To.X, step.Travel.To.Y), .. stroke.Path.Points.Select(p => new Leg(false, p.X, p.Y)), new(false, stroke.RestEnd.X, stroke.RestEnd.Y)];

                case DotProgram dots:
                    // A dot: the travel to it, then the stage stands while the gate fires.
                    return Next(ref _dots, () => dots.Steps(), done) is { } dot ? [new(true, dot.X, dot.Y)] : [];

                case RasterProgram raster:
                    // The engine counts the plan's moves, and its steps run them in the plan's order: read the plan's
                    // moves directly, not the steps, which would plan every stroke's timing once more during the run.
                    if (Next(ref _moves, () => raster.Plan.Moves(), done) is not { } move)
                    {
                        return [];
                    }

                    start = (move.X0, move.Y0);
                    return [new(move.Kind == MoveKind.Travel, move.X1, move.Y1)];

                default:
                    // No other kind of program: the hierarchy is Core's own.
                    return [];
            }
        }

        /// <summary>The item at <paramref name="index"/> (from 0), walking forward only (a new pass makes a new part); null past the end.</summary>
        private T? Next<T>(ref IEnumerator<T>? items, Func<IEnumerable<T>> all, long index)
            where T : struct
        {
            if (index < _index)
            {
                items?.Dispose();
                items = null;
                _index = -1;
            }

            items ??= all().GetEnumerator();
            while (_index < index)
            {
                if (!items.MoveNext())
                {
                    return null;
                }

                _index++;
            }

            return _index < 0 ? null : items.Current;
        }
    }
}
