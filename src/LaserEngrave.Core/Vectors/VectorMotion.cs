using System.Globalization;
using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Planning;

namespace LaserEngrave.Core.Vectors;

/// <summary>
/// Turns a <see cref="VectorPlan"/>'s paths into strokes of the two axes: each axis streams its velocity (Move At
/// Constant Speed, updated on a fixed time grid shared on the one wire), chosen so that it follows the ideal motion
/// along the path; the laser is switched by time as the stage passes the path's ends (docs/vectors.md).
/// </summary>
/// <remarks>
/// The Zaber binary protocol has no coordinated motion: each axis moves on its own and every command takes a frame
/// on the shared wire. So each axis gets a new speed every other slot (X, then Y a slot later: the second axis' later
/// start is its own time grid), aiming at the ideal position at its next update, with the ramp of its acceleration and
/// the speed's quantisation taken into account (what a speed rounds off is made up in the next interval). The same
/// model gives the estimate, so plan and run agree by construction. A corner too sharp to follow within
/// <see cref="VectorMotionOptions.DeviationLimitUm"/> splits the path there: laser off, stop, and a new stroke.
/// </remarks>
public static class VectorMotion
{
    // Time the host allows itself to react to a reply before acting on it (as TimedSwitching).
    private const double ReactionSeconds = 0.0005;

    // The spot's speed along the path may differ this much from the burn speed in the model (the pulses' spacing by as much).
    private const double SpeedTolerance = 0.06;

    /// <summary>Plans every path's strokes and adds up the time the executor takes for them.</summary>
    public static VectorSchedule Plan(VectorPlan plan, TimedSwitching timing, MachineProfile profile, VectorMotionOptions? options = null)
    {
        ArgumentNullException.ThrowIfNull(plan);
        ArgumentNullException.ThrowIfNull(timing);
        ArgumentNullException.ThrowIfNull(profile);
        options ??= VectorMotionOptions.Default;

        // Every stroke's motion is modelled before the run, command by command: the work grows with the burning time.
        var burnSeconds = plan.Paths.Sum(p => p.LengthMicrosteps) / timing.BurnSpeed;
        if (burnSeconds > DrawingLimits.MaxBurnHours * 3600)
        {
            throw new DrawingException(string.Create(
                CultureInfo.InvariantCulture,
                $"{plan.DrawingPath}: its paths take {burnSeconds / 3600:0.#} h to burn at {StageUnits.MicrostepsToMm(timing.BurnSpeed, timing.MicrostepUm):0.###} mm/s, more than the {DrawingLimits.MaxBurnHours} h a drawing job may take; give a smaller --width-mm, a higher speed, or split the drawing into layers"));
        }

        var planner = new StrokePlanner(timing, options);
        var strokes = new List<VectorStroke>();
        var skipped = new List<StagePath>();
        for (var i = 0; i < plan.Paths.Count; i++)
        {
            var path = plan.Paths[i];
            var pieces = options.StopAtEveryVertex ? Segments(path) : [path.Points];
            foreach (var piece in pieces)
            {
                foreach (var part in planner.SplitAtCorners(piece))
                {
                    planner.Add(part, path, i, strokes, skipped);
                }
            }
        }

        var warnings = new List<string>();
        if (skipped.Count > 0)
        {
            var shortest = StageUnits.MicrostepsToUm(planner.ShortestMicrosteps, timing.MicrostepUm);
            warnings.Add(string.Create(
                CultureInfo.InvariantCulture,
                $"{skipped.Count} path(s) shorter than {shortest:0.#} µm are not burned: too short to switch the laser on and off at {StageUnits.MicrostepsToMm(timing.BurnSpeed, timing.MicrostepUm):0.###} mm/s ({string.Join(", ", skipped.Take(3).Select(p => p.Source))})"));
        }

        var margin = (long)Math.Ceiling(planner.LimitMargin);
        long maxX = profile.X.TravelMicrosteps - margin, maxY = profile.Y.TravelMicrosteps - margin;
        bool Inside(StagePoint p) => p.X >= margin && p.Y >= margin && p.X <= maxX && p.Y <= maxY;
        var fits = strokes.All(s => Inside(s.RunUpStart) && Inside(s.RestEnd));
        if (!fits)
        {
            warnings.Add(string.Create(
                CultureInfo.InvariantCulture,
                $"a stroke's run-up or run-out reaches within {StageUnits.MicrostepsToUm(margin, timing.MicrostepUm):0.#} µm of the stage's travel ends (0..{profile.X.TravelMm} x 0..{profile.Y.TravelMm} mm); move --origin-mm"));
        }

        return new VectorSchedule(strokes, timing, fits, warnings, options);
    }

    private static List<IReadOnlyList<StagePoint>> Segments(StagePath path)
    {
        var list = new List<IReadOnlyList<StagePoint>>();
        for (var i = 1; i < path.Points.Count; i++)
        {
            list.Add([path.Points[i - 1], path.Points[i]]);
        }

        return list;
    }

    /// <summary>The strokes of one path and its pieces, with the grid, the ideal motion and the model.</summary>
    private sealed class StrokePlanner
    {
        private readonly TimedSwitching _t;
        private readonly VectorMotionOptions _options;
        private readonly double _slot;
        private readonly double _speed;
        private readonly double _pathAcceleration;
        private readonly double _leadSeconds;
        private readonly double _outSeconds;
        private readonly double _limit;
        private readonly double _directionLength;
        private readonly double _cornerTurn;
        private readonly UpdateGrid _grid;

        public StrokePlanner(TimedSwitching timing, VectorMotionOptions options)
        {
            _t = timing;
            _options = options;

            // One command a slot: a frame, and room for both latencies' spread so that two writes never queue on the wire.
            _slot = timing.FrameSeconds + timing.MarginSeconds;
            _grid = new UpdateGrid(_slot);
            _speed = timing.BurnSpeed;

            // The path accelerates at half the axes' acceleration, so each axis can follow it with room to correct.
            _pathAcceleration = timing.Acceleration / 2;
            var ramp = _speed / _pathAcceleration;

            // The laser comes on once the position query (third slot) has shown the stroke under way, and once the
            // axes have followed the end of the ramp for one update interval.
            var queryReply = (2 * _slot) + timing.StageReplySeconds + (2 * timing.StageJitterSeconds) + ReactionSeconds;
            var onWrite = queryReply + timing.OnLeadSeconds + timing.GateJitterSeconds - timing.OnDelaySeconds;
            _leadSeconds = Math.Max(ramp + (2 * _slot), onWrite);
            _outSeconds = ramp + (2 * _slot);
            _limit = StageUnits.UmToMicrosteps(options.DeviationLimitUm, timing.MicrostepUm);
            _directionLength = StageUnits.UmToMicrosteps(5, timing.MicrostepUm);
            ShortestMicrosteps = _speed * (timing.MinOnSeconds + timing.OnDelaySeconds + timing.OffAdvanceSeconds - (2 * timing.EdgeGuardSeconds));
            LimitMargin = (timing.BurnSpeed * timing.BurnSpeed / (2 * timing.Acceleration)) + 10;

            // The spot, within SpeedTolerance of the burn speed and each axis within its acceleration, turns on no tighter
            // radius than r = v^2 / (sqrt 2 a); an arc of that radius rounds a corner of turn t by r (1 - cos t/2), and
            // the model could share that out at best half inside, half outside the path. A corner that leaves the path by
            // more than the limit even so is one the axes cannot follow: the path is split there before its first build.
            var slowest = _speed * (1 - SpeedTolerance);
            var radius = slowest * slowest / (Math.Sqrt(2) * timing.Acceleration);
            var cosine = 1 - (2 * _limit / radius);
            _cornerTurn = cosine > -1 ? 2 * Math.Acos(cosine) : double.PositiveInfinity;
        }

        /// <summary>
        /// A path cut at each corner the axes cannot follow (<see cref="_cornerTurn"/>), where both parts are long enough to
        /// burn; what is left to split (a corner the model shows too sharp after all) is split after its build, as before.
        /// </summary>
        public IEnumerable<IReadOnlyList<StagePoint>> SplitAtCorners(IReadOnlyList<StagePoint> points)
        {
            if (points.Count <= 2 || double.IsPositiveInfinity(_cornerTurn))
            {
                yield return points;
                yield break;
            }

            var total = Length(points, 0, points.Count - 1);
            var from = 0;
            var along = 0.0;
            var fromAlong = 0.0;
            for (var k = 1; k < points.Count - 1; k++)
            {
                along += StagePoint.Distance(points[k - 1], points[k]);
                if (along - fromAlong < ShortestMicrosteps || total - along < ShortestMicrosteps || Turn(points[k - 1], points[k], points[k + 1]) <= _cornerTurn)
                {
                    continue;
                }

                yield return Slice(points, from, k);
                (from, fromAlong) = (k, along);
            }

            yield return from == 0 ? points : Slice(points, from, points.Count - 1);
        }

        private static StagePoint[] Slice(IReadOnlyList<StagePoint> points, int from, int to)
        {
            var piece = new StagePoint[to - from + 1];
            for (var k = 0; k < piece.Length; k++)
            {
                piece[k] = points[from + k];
            }

            return piece;
        }

        /// <summary>The shortest path that can be burned: the laser's least on-time at the burn speed, microsteps.</summary>
        public double ShortestMicrosteps { get; }

        /// <summary>How far from the travel's ends a stroke must stay: a constant-speed move brakes for the limit.</summary>
        public double LimitMargin { get; }

        public void Add(IReadOnlyList<StagePoint> points, StagePath source, int pathIndex, List<VectorStroke> strokes, List<StagePath> skipped)
        {
            var length = Length(points, 0, points.Count - 1);
            if (length < Math.Max(1, ShortestMicrosteps))
            {
                skipped.Add(source);
                return;
            }

            var (stroke, worst) = Build(points, source, pathIndex, strokes.Count);
            var splits = worst.Count > 0 && points.Count > 2 ? SplitPoints(points, worst) : [];
            if (splits.Count == 0)
            {
                strokes.Add(stroke);
                return;
            }

            var from = 0;
            foreach (var at in splits.Append(points.Count - 1))
            {
                Add(Slice(points, from, at), source, pathIndex, strokes, skipped);
                from = at;
            }
        }

        // For each stretch where the model leaves the path too far, the sharpest vertex near it (both parts long enough to burn).
        private List<int> SplitPoints(IReadOnlyList<StagePoint> points, IReadOnlyList<double> worst)
        {
            var along = new double[points.Count];
            for (var i = 1; i < points.Count; i++)
            {
                along[i] = along[i - 1] + StagePoint.Distance(points[i - 1], points[i]);
            }

            // After a sharp turn the axes take several updates to settle: the worst can come well after the corner.
            var window = _speed * 16 * _slot;
            var splits = new SortedSet<int>();
            foreach (var at in worst)
            {
                var best = -1;
                var sharpest = 0.0;

                // Only the vertices within the window: found by bisection (along is sorted), so many corners cost no square.
                var first = Array.BinarySearch(along, at - window);
                first = Math.Max(1, first < 0 ? ~first : first);
                for (var k = first; k < points.Count - 1 && along[k] <= at + window; k++)
                {
                    if (Math.Abs(along[k] - at) > window || along[k] < ShortestMicrosteps || along[^1] - along[k] < ShortestMicrosteps)
                    {
                        continue;
                    }

                    var turn = Turn(points[k - 1], points[k], points[k + 1]);
                    if (turn > sharpest)
                    {
                        (sharpest, best) = (turn, k);
                    }
                }

                if (best > 0)
                {
                    splits.Add(best);
                }
            }

            return [.. splits];
        }

        private (VectorStroke Stroke, IReadOnlyList<double> Worst) Build(IReadOnlyList<StagePoint> points, StagePath source, int pathIndex, int index)
        {
            var first = points[0];
            var last = points[^1];
            var (ux0, uy0) = Direction(points, forward: true);
            var (ux1, uy1) = Direction(points, forward: false);
            var runUp = (_speed * _speed / (2 * _pathAcceleration)) + (_speed * (_leadSeconds - (_speed / _pathAcceleration)));
            var runOut = (_speed * _speed / (2 * _pathAcceleration)) + (_speed * (_outSeconds - (_speed / _pathAcceleration)));
            var start = (first.X - (ux0 * runUp), first.Y - (uy0 * runUp));
            var end = (last.X + (ux1 * runOut), last.Y + (uy1 * runOut));
            var polyline = new List<(double X, double Y)>(points.Count + 2) { start };
            foreach (var p in points)
            {
                polyline.Add((p.X, p.Y));
            }

            polyline.Add(end);

            // The axes stand on whole microsteps: the stroke starts from the rounded run-up start.
            var runUpStart = new StagePoint(JobGeometry.Round(start.Item1), JobGeometry.Round(start.Item2));
            polyline[0] = (runUpStart.X, runUpStart.Y);
            var ideal = new StrokeProfile(polyline, _speed, _pathAcceleration);
            var pathStart = ideal.LengthAt(1);
            var pathEnd = ideal.LengthAt(points.Count);
            var on = ideal.TimeAtDistance(pathStart) + _t.OnDelaySeconds;
            var off = ideal.TimeAtDistance(pathEnd) - _t.OffAdvanceSeconds;

            var queryAxis = Math.Abs(ux0) >= Math.Abs(uy0) ? VectorAxis.X : VectorAxis.Y;
            var xs = Follow(ideal, VectorAxis.X, runUpStart.X, 0, out var restX, out var xAtRest);
            var ys = Follow(ideal, VectorAxis.Y, runUpStart.Y, _slot, out var restY, out var yAtRest);
            var query = new AxisCommand(2 * _slot, queryAxis, AxisCommandKind.Query);
            var commands = Merge(xs, ys, query);
            var expected = Replay(queryAxis == VectorAxis.X ? xs : ys, queryAxis == VectorAxis.X ? runUpStart.X : runUpStart.Y, query.AtSeconds);

            // The model against the path while the laser is on, piece by piece of its motion: the stretches too far from it.
            var window = _speed * 4 * _slot;
            var check = StrokeCheck.Run(ideal, xs, ys, runUpStart, on, off, _t.Acceleration, _limit, SpeedTolerance, window, pathStart, pathEnd);
            var (worst, largest) = check.GaveUp
                ? Sampled(ideal, xs, ys, runUpStart, on, off, window, pathStart, pathEnd)
                : (check.Worst, check.Largest);

            var rest = Math.Max(restX, restY);
            var stroke = new VectorStroke
            {
                Index = index,
                PathIndex = pathIndex,
                Path = source with { Points = points, Closed = points.Count > 3 && points[0] == points[^1] },
                RunUpStart = runUpStart,
                RestEnd = new StagePoint(xAtRest, yAtRest),
                Commands = new StrokeCommands(commands, _grid),
                QueryExpected = expected,
                LaserOnSeconds = on,
                LaserOffSeconds = off,
                RestSeconds = rest,
                NextArrivalSeconds = Math.Max(rest + _t.MarginSeconds, off + _t.AfterOffSeconds),
                PredictedDeviationUm = StageUnits.MicrostepsToUm(largest, _t.MicrostepUm),
            };
            return (stroke, worst);
        }

        // The model against the path every StrokeCheck.SampleSeconds while the laser is on (for a path too dense for the
        // check by pieces): the stretches too far from it, as the check was first made.
        private (List<double> Worst, double Largest) Sampled(StrokeProfile ideal, List<AxisCommand> xs, List<AxisCommand> ys, StagePoint runUpStart, double on, double off, double window, double pathStart, double pathEnd)
        {
            var worst = new List<double>();
            var largest = 0.0;
            var x = new AxisModel(runUpStart.X, _t.Acceleration);
            var y = new AxisModel(runUpStart.Y, _t.Acceleration);
            int xi = 0, yi = 0;
            var over = false;
            (double Deviation, double At) peak = (0, 0);
            for (var t = on; t <= off; t += StrokeCheck.SampleSeconds)
            {
                while (xi < xs.Count && xs[xi].AtSeconds <= t)
                {
                    x.Apply(xs[xi++]);
                }

                while (yi < ys.Count && ys[yi].AtSeconds <= t)
                {
                    y.Apply(ys[yi++]);
                }

                x.AdvanceTo(t);
                y.AdvanceTo(t);
                var s = ideal.DistanceAt(t);
                var d = ideal.DistanceFollowing(x.Position, y.Position, Math.Max(pathStart, s - window), Math.Min(pathEnd, s + window));
                largest = Math.Max(largest, d);

                // A corner the axes round within the limit can still slow the spot down or speed it up: the pulses bunch.
                var speedError = Math.Abs((Math.Sqrt((x.Velocity * x.Velocity) + (y.Velocity * y.Velocity)) / _speed) - 1);
                if (d > _limit || speedError > SpeedTolerance)
                {
                    over = true;
                    var badness = Math.Max(d / _limit, speedError / SpeedTolerance);
                    if (badness > peak.Deviation)
                    {
                        peak = (badness, s - pathStart);
                    }
                }
                else if (over)
                {
                    worst.Add(peak.At);
                    (over, peak) = (false, (0, 0));
                }
            }

            if (over)
            {
                worst.Add(peak.At);
            }

            return (worst, largest);
        }

        /// <summary>One axis' commands: a new speed at each of its updates (when it changes), then a stop once the ideal motion rests.</summary>
        private List<AxisCommand> Follow(StrokeProfile ideal, VectorAxis axis, long start, double firstUpdate, out double restSeconds, out long restPosition)
        {
            var commands = new List<AxisCommand>();
            var model = new AxisModel(start, _t.Acceleration);
            var data = 0;
            double Coordinate(double seconds)
            {
                var (x, y) = ideal.PositionAt(seconds);
                return axis == VectorAxis.X ? x : y;
            }

            // X updates at slots 0, 3, 5, 7, ...; Y at 1, 4, 6, 8, ...: slot 2 carries the position query.
            var update = firstUpdate;
            while (true)
            {
                var next = update + (update < 2 * _slot ? 3 * _slot : 2 * _slot);
                model.AdvanceTo(update);
                if (update >= ideal.DurationSeconds)
                {
                    if (!model.AtRest || data != 0)
                    {
                        var stop = new AxisCommand(update, axis, AxisCommandKind.Stop);
                        commands.Add(stop);
                        model.Apply(stop);
                    }

                    break;
                }

                var speed = model.SpeedToReach(Coordinate(next), next - update);
                var wanted = StageUnits.SignedSpeedData(speed);
                if (wanted != data)
                {
                    var command = wanted == 0 ? new AxisCommand(update, axis, AxisCommandKind.Stop) : new AxisCommand(update, axis, AxisCommandKind.Speed, wanted);
                    commands.Add(command);
                    model.Apply(command);
                    data = wanted;
                }

                update = next;
            }

            restSeconds = model.SettledSeconds;
            model.AdvanceTo(restSeconds + 1e-9);
            restPosition = JobGeometry.Round(model.Position);
            return commands;
        }

        private long Replay(List<AxisCommand> commands, long start, double seconds)
        {
            var model = new AxisModel(start, _t.Acceleration);
            foreach (var command in commands)
            {
                if (command.AtSeconds > seconds)
                {
                    break;
                }

                model.Apply(command);
            }

            model.AdvanceTo(seconds);
            return JobGeometry.Round(model.Position);
        }

        // Every command in time order: X before Y before the query at the same time (as a stable sort of them in that order).
        private static AxisCommand[] Merge(List<AxisCommand> xs, List<AxisCommand> ys, AxisCommand query)
        {
            var all = new AxisCommand[xs.Count + ys.Count + 1];
            int xi = 0, yi = 0;
            var queried = false;
            for (var k = 0; k < all.Length; k++)
            {
                var tx = xi < xs.Count ? xs[xi].AtSeconds : double.PositiveInfinity;
                var ty = yi < ys.Count ? ys[yi].AtSeconds : double.PositiveInfinity;
                var tq = queried ? double.PositiveInfinity : query.AtSeconds;
                if (tx <= ty && tx <= tq)
                {
                    all[k] = xs[xi++];
                }
                else if (ty <= tq)
                {
                    all[k] = ys[yi++];
                }
                else
                {
                    (all[k], queried) = (query, true);
                }
            }

            return all;
        }

        // The unit direction at a path's start (forward) or end, over its first (last) 5 µm, so a one-microstep segment does not decide it.
        private (double X, double Y) Direction(IReadOnlyList<StagePoint> points, bool forward)
        {
            var from = forward ? points[0] : points[^1];
            var to = from;
            for (var k = 1; k < points.Count; k++)
            {
                to = forward ? points[k] : points[^(k + 1)];
                if (StagePoint.Distance(from, to) >= _directionLength)
                {
                    break;
                }
            }

            var d = StagePoint.Distance(from, to);
            return forward ? ((to.X - from.X) / d, (to.Y - from.Y) / d) : ((from.X - to.X) / d, (from.Y - to.Y) / d);
        }

        private static double Length(IReadOnlyList<StagePoint> points, int from, int to)
        {
            var length = 0.0;
            for (var i = from + 1; i <= to; i++)
            {
                length += StagePoint.Distance(points[i - 1], points[i]);
            }

            return length;
        }

        private static double Turn(StagePoint a, StagePoint b, StagePoint c)
        {
            double x1 = b.X - a.X, y1 = b.Y - a.Y, x2 = c.X - b.X, y2 = c.Y - b.Y;
            return Math.Abs(Math.Atan2((x1 * y2) - (y1 * x2), (x1 * x2) + (y1 * y2)));
        }
    }
}
