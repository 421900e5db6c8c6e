using LaserEngrave.Core.Geometry;

namespace LaserEngrave.Core.Planning;

/// <summary>
/// The program of a raster pass: under timed switching its travels and strokes (<see cref="StrokeStep"/>: runs, flown
/// gaps, the stroke's motion and its first and last edge), step by step (a paper plan, or one without a timing model)
/// its plain moves. Made streaming from the plan's moves, row by row, never held whole.
/// </summary>
/// <remarks>
/// The executor sends these steps (Devices/Execution/RunExecutor.Timed and .StepByStep) and <see cref="PlanEstimator"/>
/// interprets the same steps against the motion model, so the estimate is of what is sent. A stroke is the plan's moves
/// between two travels in one row and one direction, in one piece.
/// </remarks>
public sealed class RasterProgram : PartProgram
{
    /// <param name="plan">The raster plan.</param>
    /// <param name="process">Speeds, acceleration, frequency and baud rates.</param>
    /// <param name="gate">The gate's command strings (default: <see cref="LaserGateProfile"/>'s defaults).</param>
    /// <param name="timing">The timing model strokes are planned by (default: the plan's; a run that times itself with
    /// wider latencies gives its own). Ignored for a plan without one: its program is step by step.</param>
    public RasterProgram(RasterPlan plan, ProcessSettings process, LaserGateProfile? gate = null, TimedSwitching? timing = null)
        : base(process, Validated(plan).Options.Strategy, plan.Geometry.MicrostepUm, gate ?? new LaserGateProfile())
    {
        Plan = plan;
        Timing = plan.Timing is null ? null : timing ?? plan.Timing;

        // The plan's run-up, also when the run times itself with wider latencies: the travels before the strokes end where the plan put them.
        RunUpMicrosteps = plan.Timing?.RunUpMicrosteps ?? 0;
        _rowEstimates = new Lazy<PlanEstimator[]>(EstimateRowStarts);
    }

    private readonly Lazy<PlanEstimator[]> _rowEstimates;

    public RasterPlan Plan { get; }

    /// <summary>The timing model of a timed program; null: step by step.</summary>
    public TimedSwitching? Timing { get; }

    public override TimedSwitching? SwitchTiming => Timing;

    /// <summary>The same plan's program timed by another model (a run that times itself with wider latencies).</summary>
    public RasterProgram Retimed(TimedSwitching? timing) => new(Plan, Process, Gate, timing);

    /// <summary>The run-up a stroke gets before its first edge when its first move is shorter, microsteps.</summary>
    public long RunUpMicrosteps { get; }

    /// <summary>Every step in order; each stroke owns its buffers.</summary>
    public IEnumerable<RasterStep> Steps() => Enumerate(Plan.Moves(), 0, null);

    /// <summary>The steps from a stop point on (<see cref="ResumeAt"/>): a burn run cut off midway starts at its resume X with a run-up before it.</summary>
    public IEnumerable<RasterStep> Steps(RasterResume from)
    {
        ArgumentNullException.ThrowIfNull(from);
        if (from.Done)
        {
            return [];
        }

        return Enumerate(MovesFrom(from.FirstMoveIndex), from.FirstMoveIndex, from.Trimmed);
    }

    /// <summary>Passes every step in order to <paramref name="visitor"/>, reusing one stroke's buffers: nothing is allocated per step.</summary>
    /// <returns>The number of the plan's rows visited.</returns>
    public int Visit<TVisitor>(ref TVisitor visitor)
        where TVisitor : IRasterStepVisitor
    {
        var feeder = new Feeder<TVisitor>(new StepBuilder(this, reuse: true), visitor);
        var rows = Plan.VisitRows(ref feeder);
        feeder.Builder.Finish(ref feeder.Visitor);
        visitor = feeder.Visitor;
        return rows;
    }

    /// <summary>
    /// Where the program goes on from <paramref name="stop"/>: a burn run is resumed with its run-up, as it was planned; one
    /// cut off midway (<paramref name="resumeX"/>), from its first pixel not completely burned.
    /// </summary>
    /// <remarks>Found from the plan's row index (<see cref="PlanRowIndex"/>): only the stop point's row is planned again.</remarks>
    /// <exception cref="PlanException">The stop point is not in this plan, or the resume X not inside its burn run.</exception>
    public RasterResume ResumeAt(RunStopPoint stop, long? resumeX)
    {
        ArgumentNullException.ThrowIfNull(stop);
        var index = Plan.RowIndex;
        var rows = index.Rows;
        var moveCount = index.MoveCount;
        var start = stop.MoveIndex;
        Move? trimmed = null;
        if (stop.MoveIndex >= 0 && stop.MoveIndex < moveCount)
        {
            var row = rows[index.RowHolding(stop.MoveIndex)];
            var moves = PlanRowIndex.RowMoves(Plan, row);
            var at = checked((int)(stop.MoveIndex - row.MoveIndex));
            var move = moves[at];
            if (resumeX is { } x)
            {
                var dir = Math.Sign(move.X1 - move.X0);
                if (move.Kind != MoveKind.Burn || (x - move.X0) * dir <= 0 || (move.X1 - x) * dir <= 0)
                {
                    throw new PlanException($"the resume point (row {stop.Row}, move {stop.MoveIndex}, X {x}) is not inside a burn run of this job's plan");
                }

                trimmed = move with { X0 = x };
            }
            else if (move.Kind == MoveKind.Burn && at > 0 && moves[at - 1] is { Kind: MoveKind.Overscan } runUp && runUp.Row == move.Row)
            {
                // A run-up is in its run's row: the move before a row's first is never one.
                start--;
            }
        }

        // Where the stop point's row starts (or the first row with moves after it).
        var first = index.FirstRowFrom(stop.Row);
        var rowStart = first < rows.Count ? rows[first].MoveIndex : -1;
        if (start < 0 || start > moveCount || (start < moveCount && (rowStart < 0 || rowStart > start)))
        {
            throw new PlanException($"the resume point (row {stop.Row}, move {stop.MoveIndex}) is not in this job's plan of {moveCount} moves");
        }

        // What was done before the resume point: the counts at its row's start, then that row's moves before it.
        var counter = new PlanRowIndex.Counter();
        if (start > 0)
        {
            var row = rows[index.RowHolding(start - 1)];
            counter = new PlanRowIndex.Counter(row);
            foreach (var move in PlanRowIndex.RowMoves(Plan, row))
            {
                if (counter.Index >= start)
                {
                    break;
                }

                counter.Visit(move);
            }
        }

        return new RasterResume(stop, start, trimmed, rowStart, moveCount, counter.Runs, counter.Rows, counter.LastRow);
    }

    /// <summary>
    /// The estimate of a resumed run: of the program up to the resume point, as the run had it when its last move there ended (a
    /// stroke not finished counted at the burn speed from its start), and of the steps from there (<see cref="Steps(RasterResume)"/>).
    /// </summary>
    /// <remarks>
    /// The part before goes on from the estimate kept at the start of the resume point's row (<see cref="RowEstimates"/>,
    /// made once for the program), so it costs a row; the part after costs the rows left.
    /// </remarks>
    public (double Before, double Remaining) EstimateResumed(RasterResume from)
    {
        ArgumentNullException.ThrowIfNull(from);
        var before = 0.0;
        var index = Plan.RowIndex;

        // Strokes never span rows, so every step before the last row start below the resume point is in the kept estimate;
        // a stroke ending just at the resume point is counted provisionally, as the run had it: that row is gone over again.
        var k = index.RowHolding(from.FirstMoveIndex, strictly: true);
        if (k >= 0)
        {
            var row = index.Rows[k];
            var kept = RowEstimates[k].Clone();
            var visitor = new BeforeVisitor(kept, from.FirstMoveIndex, kept.ElapsedSeconds - kept.StartSeconds);
            var rowBuilder = new StepBuilder(this, reuse: true);
            var at = row.MoveIndex;
            foreach (var move in PlanRowIndex.RowMoves(Plan, row))
            {
                rowBuilder.Add(move, at++, ref visitor);
            }

            rowBuilder.Finish(ref visitor);
            before = visitor.Seconds;
        }

        var remaining = new PlanEstimator(this);
        var collector = new EstimatingVisitor(remaining);
        var builder = new StepBuilder(this, reuse: true);
        var moveIndex = from.FirstMoveIndex;
        if (!from.Done)
        {
            var first = true;
            foreach (var move in MovesFrom(from.FirstMoveIndex))
            {
                builder.Add(first && from.Trimmed is { } trimmed ? trimmed : move, moveIndex++, ref collector);
                first = false;
            }

            builder.Finish(ref collector);
        }

        remaining.Finish();
        return (before, remaining.ElapsedSeconds);
    }

    /// <summary>
    /// The estimator as it stood at the start of each row of the plan's <see cref="PlanRowIndex"/>, every step before that
    /// row added: one pass over the program, made on the first resume and kept for the next ones.
    /// </summary>
    private PlanEstimator[] RowEstimates => _rowEstimates.Value;

    private PlanEstimator[] EstimateRowStarts()
    {
        var rows = Plan.RowIndex.Rows;
        var kept = new PlanEstimator[rows.Count];
        var estimator = new PlanEstimator(this);
        var visitor = new EstimatingVisitor(estimator);
        var builder = new StepBuilder(this, reuse: true);
        for (var k = 0; k < rows.Count; k++)
        {
            // The stroke before ends here: a row's first move never joins it (strokes stay in their row).
            builder.Finish(ref visitor);
            kept[k] = estimator.Clone();
            var at = rows[k].MoveIndex;
            foreach (var move in PlanRowIndex.RowMoves(Plan, rows[k]))
            {
                builder.Add(move, at++, ref visitor);
            }
        }

        return kept;
    }

    /// <summary>The plan's moves from index <paramref name="first"/> on, planned from that move's row.</summary>
    private IEnumerable<Move> MovesFrom(long first)
    {
        var index = Plan.RowIndex;
        if (first >= index.MoveCount)
        {
            return [];
        }

        var row = index.Rows[index.RowHolding(first)];
        return PlanRowIndex.MovesFrom(Plan, row).Skip(checked((int)(first - row.MoveIndex)));
    }

    private static RasterPlan Validated(RasterPlan plan)
    {
        ArgumentNullException.ThrowIfNull(plan);
        return plan;
    }

    private IEnumerable<RasterStep> Enumerate(IEnumerable<Move> moves, long firstIndex, Move? trimmedFirst)
    {
        var builder = new StepBuilder(this, reuse: false);
        var collector = new Collector();
        var index = firstIndex;
        foreach (var move in moves)
        {
            builder.AddTo(index == firstIndex && trimmedFirst is { } trimmed ? trimmed : move, index, collector);
            index++;
            foreach (var step in collector.Steps)
            {
                yield return step;
            }

            collector.Steps.Clear();
        }

        builder.FinishTo(collector);
        foreach (var step in collector.Steps)
        {
            yield return step;
        }
    }

    /// <summary>Turns the plan's moves into steps: the one place strokes are assembled.</summary>
    private sealed class StepBuilder(RasterProgram program, bool reuse)
    {
        private readonly TimedSwitching? _timing = program.Timing;
        private readonly MotionData _motion = program.Motion;
        private readonly long _travelX = program.Plan.Geometry.TravelXMicrosteps;
        private StrokeStep? _reused;
        private StrokeStep? _open;

        public void AddTo(in Move move, long index, Collector collector) => Add(move, index, ref collector);

        public void FinishTo(Collector collector) => Finish(ref collector);

        public void Add<TVisitor>(in Move move, long index, ref TVisitor visitor)
            where TVisitor : IRasterStepVisitor
        {
            if (_timing is null)
            {
                visitor.Move(new MoveStep(move.Kind == MoveKind.Burn, move.X1, move.Y1, _motion.SpeedDataFor(move.Kind), move, index));
                return;
            }

            if (move.Kind == MoveKind.Travel)
            {
                Finish(ref visitor);
                visitor.Travel(new TravelStep(move.X1, move.Y1, _motion.TravelSpeedData, move, index));
                return;
            }

            if (_open is { } open)
            {
                ref readonly var last = ref open.Last;
                if (last.Row == move.Row && last.X1 == move.X0 && last.Y1 == move.Y0 && Math.Sign(last.X1 - last.X0) == Math.Sign(move.X1 - move.X0))
                {
                    open.Add(move);
                    return;
                }

                Finish(ref visitor);
            }

            var stroke = reuse ? _reused ??= new StrokeStep() : new StrokeStep();
            stroke.Begin(index);
            stroke.Add(move);
            _open = stroke;
        }

        public void Finish<TVisitor>(ref TVisitor visitor)
            where TVisitor : IRasterStepVisitor
        {
            if (_open is not { } stroke)
            {
                return;
            }

            _open = null;
            stroke.Close(_timing!, program.RunUpMicrosteps, _travelX, reuse);
            visitor.Stroke(stroke);
        }
    }

    private struct Feeder<TVisitor>(StepBuilder builder, TVisitor visitor) : IMoveVisitor
        where TVisitor : IRasterStepVisitor
    {
        public readonly StepBuilder Builder = builder;
        public TVisitor Visitor = visitor;
        private long _index;

        public void Visit(in Move move) => Builder.Add(move, _index++, ref Visitor);
    }

    private sealed class Collector : IRasterStepVisitor
    {
        public List<RasterStep> Steps { get; } = [];

        public void Travel(in TravelStep travel) => Steps.Add(RasterStep.Of(travel));

        public void Stroke(StrokeStep stroke) => Steps.Add(RasterStep.Of(stroke));

        public void Move(in MoveStep move) => Steps.Add(RasterStep.Of(move));
    }

    private readonly struct EstimatingVisitor(PlanEstimator estimator) : IRasterStepVisitor
    {
        public void Travel(in TravelStep travel) => estimator.Travel(travel);

        public void Stroke(StrokeStep stroke) => estimator.Stroke(stroke);

        public void Move(in MoveStep move) => estimator.Move(move);
    }

    // The estimate up to a move index as the run had it then: every step before it, a stroke it falls in (or the last
    // before it) provisionally.
    private struct BeforeVisitor(PlanEstimator estimator, long firstIndex, double seconds) : IRasterStepVisitor
    {
        public double Seconds { get; private set; } = seconds;

        public void Travel(in TravelStep travel)
        {
            if (travel.MoveIndex < firstIndex)
            {
                estimator.Travel(travel);
                Seconds = estimator.ElapsedSeconds - estimator.StartSeconds;
            }
        }

        public void Stroke(StrokeStep stroke)
        {
            var end = stroke.FirstMoveIndex + stroke.MoveCount;
            if (end < firstIndex)
            {
                estimator.Stroke(stroke);
                Seconds = estimator.ElapsedSeconds - estimator.StartSeconds;
            }
            else if (stroke.FirstMoveIndex < firstIndex)
            {
                Seconds = estimator.Provisional(stroke, checked((int)(firstIndex - stroke.FirstMoveIndex))) - estimator.StartSeconds;
            }
        }

        public void Move(in MoveStep move)
        {
            if (move.MoveIndex < firstIndex)
            {
                estimator.Move(move);
                Seconds = estimator.ElapsedSeconds - estimator.StartSeconds;
            }
        }
    }
}
