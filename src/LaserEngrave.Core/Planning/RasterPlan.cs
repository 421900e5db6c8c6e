using System.Globalization;
using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Imaging;

namespace LaserEngrave.Core.Planning;

/// <summary>A raster plan: a mask, where it lands on the stage and how it is scanned; its moves are generated row by row on demand, never held whole.</summary>
/// <remarks>
/// Every position comes from <see cref="JobGeometry"/>'s edge formula, rounded once. Moves of zero length are left out.
/// A move's <see cref="Move.Row"/> is the image row it burns on, or for a travel between rows the row it leads to.
/// The plan begins at the first move's start; reaching it is the executor's business.
/// <see cref="PlanStrategy.Paper"/> ignores <see cref="PlanOptions.Bidirectional"/> and <see cref="PlanOptions.OverscanMm"/>.
/// A scan offset shifts every X position of the right-to-left rows (edges, run-ups, run-outs) before the one rounding;
/// rows burned left to right, and every row of a unidirectional or paper plan, are left as they are.
/// The plan reads the mask each time it is enumerated, so the mask must not change while the plan is in use.
/// </remarks>
public sealed class RasterPlan
{
    /// <param name="mask">What to burn.</param>
    /// <param name="geometry">Where the mask lands on the stage.</param>
    /// <param name="options">Strategy, scan direction, overscan.</param>
    /// <param name="scanOffsetUm">Shift of right-to-left rows' X edges, µm, positive towards +X: the machine profile's
    /// scan offset at the burn speed (<see cref="MachineProfile.ScanOffsetUmAt"/>).</param>
    /// <param name="timing">The timing model of timed switching (run-ups, gap choices, the estimate); null: moves only.</param>
    public RasterPlan(BitMask mask, JobGeometry geometry, PlanOptions? options = null, double scanOffsetUm = 0, TimedSwitching? timing = null)
    {
        ArgumentNullException.ThrowIfNull(mask);
        ArgumentNullException.ThrowIfNull(geometry);
        options ??= PlanOptions.Default;
        options.Validate();
        if (mask.Width != geometry.WidthPx || mask.Height != geometry.HeightPx)
        {
            throw new PlanException($"the mask is {mask.Width} x {mask.Height} pixels but the geometry is for {geometry.WidthPx} x {geometry.HeightPx}");
        }

        if (!double.IsFinite(scanOffsetUm))
        {
            throw new PlanException($"scan offset {scanOffsetUm.ToString(CultureInfo.InvariantCulture)} µm must be a finite number");
        }

        Mask = mask;
        Geometry = geometry;
        Options = options;
        ScanOffsetUm = scanOffsetUm;
        OverscanMicrosteps = options.Strategy == PlanStrategy.Paper
            ? 0
            : JobGeometry.Round(StageUnits.MmToMicrosteps(options.OverscanMm, geometry.MicrostepUm));
        Timing = options.Strategy == PlanStrategy.Optimized ? timing : null;
        _switchingProblem = new Lazy<string?>(FindSwitchingProblem);
        _rowIndex = new Lazy<PlanRowIndex>(() => PlanRowIndex.Build(this));
        RunUpMicrosteps = Math.Max(OverscanMicrosteps, Timing?.RunUpMicrosteps ?? 0);
        RunOutMicrosteps = Math.Max(OverscanMicrosteps, Timing?.RunOutMicrosteps ?? 0);
        Warnings = [.. OverscanWarnings(), .. ScanOffsetWarnings()];
    }

    public BitMask Mask { get; }

    public JobGeometry Geometry { get; }

    public PlanOptions Options { get; }

    /// <summary>Shift of the right-to-left rows' X edges, µm, positive towards +X (0: none).</summary>
    public double ScanOffsetUm { get; }

    /// <summary>Overscan length in whole microsteps (0 under <see cref="PlanStrategy.Paper"/>).</summary>
    public long OverscanMicrosteps { get; }

    /// <summary>
    /// The timing model the plan was made for (run-ups long enough for timed laser switching, gaps crossed or travelled
    /// whichever is faster); null for <see cref="PlanStrategy.Paper"/> or when planned without one (moves only).
    /// </summary>
    private readonly Lazy<string?> _switchingProblem;
    private readonly Lazy<PlanRowIndex> _rowIndex;

    public TimedSwitching? Timing { get; }

    /// <summary>Null when timed switching can switch one pixel exactly at the burn speed; otherwise why not, in one line.</summary>
    /// <remarks>
    /// Every switch-on is a counted burst whose line grows with its count (docs/execution.md, "The burst"): the gap before
    /// a switch-on must carry the longest such line of the job, that of its longest run, and no run may need more pulses
    /// than the gate counts in one burst.
    /// </remarks>
    public string? SwitchingProblem => _switchingProblem.Value;

    private string? FindSwitchingProblem()
    {
        if (Timing is not { } timing)
        {
            return null;
        }

        var longest = (long)Math.Ceiling(LongestRunPixels() * Geometry.PitchXMicrosteps);
        return timing.RunTooLongForBurst(longest)
            ?? timing.PixelTooShort((long)Math.Floor(Geometry.PitchXMicrosteps), Geometry.PitchUm, longest);
    }

    // The widest run of black pixels of any row.
    private int LongestRunPixels()
    {
        var runs = new int[64];
        var longest = 0;
        for (var y = 0; y < Mask.Height; y++)
        {
            var count = RowRuns.Find(Mask.ReadRow(y), ref runs);
            for (var i = 0; i < count; i++)
            {
                longest = Math.Max(longest, runs[(2 * i) + 1] - runs[2 * i]);
            }
        }

        return longest;
    }

    /// <summary>Run-up before each row's first burn run, microsteps: the overscan, or longer when timed switching needs it.</summary>
    public long RunUpMicrosteps { get; }

    /// <summary>Run-out after each row's last burn run, microsteps.</summary>
    public long RunOutMicrosteps { get; }

    /// <summary>Warnings about the plan itself (the geometry's own are in its <see cref="GeometryReport"/>).</summary>
    public IReadOnlyList<JobWarning> Warnings { get; }

    /// <summary>Every move in order, generated row by row.</summary>
    public IEnumerable<Move> Moves() => Moves(0);

    /// <summary>
    /// The moves tagged with row <paramref name="fromRow"/> or later, in order: the same moves as <see cref="Moves()"/> from
    /// that point, beginning with the travel into the first visited row at or after <paramref name="fromRow"/>. For resuming a run.
    /// </summary>
    public IEnumerable<Move> Moves(int fromRow)
    {
        ArgumentOutOfRangeException.ThrowIfNegative(fromRow);
        ArgumentOutOfRangeException.ThrowIfGreaterThan(fromRow, Mask.Height);
        return Enumerate(fromRow);
    }

    /// <summary>Passes every move in order to <paramref name="visitor"/>; with a struct visitor nothing is allocated per move.</summary>
    public void Visit<TVisitor>(ref TVisitor visitor)
        where TVisitor : IMoveVisitor => VisitRows(ref visitor);

    /// <summary><see cref="Visit{TVisitor}(ref TVisitor)"/>; returns the number of rows visited.</summary>
    internal int VisitRows<TVisitor>(ref TVisitor visitor)
        where TVisitor : IMoveVisitor
    {
        var planner = NewPlanner();
        while (planner.NextRow < Mask.Height)
        {
            planner.PlanNextRow(ref visitor);
        }

        return planner.VisitedRows;
    }

    /// <summary>The visited rows in order with the index and count of their moves (progress, and the move index to row map for resume).</summary>
    public IEnumerable<PlanRow> Rows()
    {
        var planner = NewPlanner();
        var counter = new CountingVisitor();
        long index = 0;
        while (planner.NextRow < Mask.Height)
        {
            var row = planner.NextRow;
            counter.Count = 0;
            if (planner.PlanNextRow(ref counter))
            {
                yield return new PlanRow(row, planner.LastRowLeftToRight, index, counter.Count);
                index += counter.Count;
            }
        }
    }

    /// <summary>Rows, runs, lengths, laser switches and the estimated duration under <paramref name="process"/>, in one streaming pass.</summary>
    /// <param name="process">Speeds, acceleration, frequency and baud rates.</param>
    /// <param name="gate">The gate's command strings (default: <see cref="LaserGateProfile"/>'s defaults).</param>
    public PlanStatistics ComputeStatistics(ProcessSettings process, LaserGateProfile? gate = null)
    {
        // The estimate interprets the program the executor sends (Programs/RasterProgram), step by step.
        var program = new RasterProgram(this, process, gate);
        var visitor = new StatisticsVisitor(new PlanEstimator(program), new LowerBound(process, Geometry.MicrostepUm));
        var rows = program.Visit(ref visitor);
        var statistics = visitor.Finish(rows, Geometry.MicrostepUm);
        if (Timing is null || visitor.Start is not { } start)
        {
            return statistics;
        }

        return statistics with
        {
            PreparationSeconds = Timing.PreparationSeconds(start.X, start.Y, home: true, from: (0, 0)),
            PassSetupSeconds = Timing.PreparationSeconds(start.X, start.Y, home: false, from: visitor.End),
            Ends = (start, visitor.End),
        };
    }

    private IEnumerable<Move> Enumerate(int fromRow)
    {
        var planner = NewPlanner();
        var skipped = default(NullVisitor);
        while (planner.NextRow < fromRow)
        {
            planner.PlanNextRow(ref skipped);
        }

        // One row's moves at a time: bounded by the width, however tall the mask.
        var buffer = new BufferVisitor();
        while (planner.NextRow < Mask.Height)
        {
            buffer.Moves.Clear();
            planner.PlanNextRow(ref buffer);
            foreach (var move in buffer.Moves)
            {
                yield return move;
            }
        }
    }

    /// <summary>
    /// Where a burn run cut off after the laser burned it up to <paramref name="burnedUpTo"/> (stage X, microsteps) goes
    /// on: the entry edge of the first pixel not completely burned, and that pixel's column (the one burned twice); null
    /// when no pixel of the run was completely burned.
    /// </summary>
    public (long ResumeX, int Column)? ResumeWithin(in Move burn, double burnedUpTo)
    {
        if (burn.Kind != MoveKind.Burn || burn.X0 == burn.X1)
        {
            throw new ArgumentException("a burn run along X is needed", nameof(burn));
        }

        var leftToRight = burn.X1 > burn.X0;
        var offset = leftToRight ? 0 : StageUnits.UmToMicrosteps(ScanOffsetUm, Geometry.MicrostepUm);
        (long X, int Column)? best = null;
        for (var c = 0; c <= Geometry.WidthPx; c++)
        {
            var b = Geometry.RunEdgeX(c, burn.Row, offset);
            var inside = leftToRight ? b > burn.X0 && b < burn.X1 && b <= burnedUpTo : b < burn.X0 && b > burn.X1 && b >= burnedUpTo;
            if (inside && (best is null || (leftToRight ? b > best.Value.X : b < best.Value.X)))
            {
                best = (b, leftToRight ? c : c - 1);
            }
        }

        return best;
    }

    /// <summary>The pixel column of a burn run along X that holds <paramref name="x"/> (microsteps, within the run).</summary>
    public int ColumnAt(in Move burn, double x)
    {
        if (burn.Kind != MoveKind.Burn || burn.X0 == burn.X1)
        {
            throw new ArgumentException("a burn run along X is needed", nameof(burn));
        }

        var leftToRight = burn.X1 > burn.X0;
        var offset = leftToRight ? 0 : StageUnits.UmToMicrosteps(ScanOffsetUm, Geometry.MicrostepUm);
        var column = 0;
        for (var c = 0; c <= Geometry.WidthPx; c++)
        {
            // The last pixel edge at or before x: x lies in the pixel after it.
            if (Geometry.RunEdgeX(c, burn.Row, offset) <= x)
            {
                column = c;
            }
        }

        return Math.Clamp(column, 0, Geometry.WidthPx - 1);
    }

    /// <summary>Where each visited row starts (built on first use, by one pass of the planner): for resuming without planning the rows before.</summary>
    internal PlanRowIndex RowIndex => _rowIndex.Value;

    internal RowPlanner NewPlanner() => new(Mask, Geometry, Options, OverscanMicrosteps, StageUnits.UmToMicrosteps(ScanOffsetUm, Geometry.MicrostepUm), Timing);

    private List<JobWarning> OverscanWarnings()
    {
        var warnings = new List<JobWarning>();
        if (Timing is not null && TimedRoomWarning() is { } timed)
        {
            warnings.Add(timed);
        }

        if (SwitchingProblem is { } tooShort)
        {
            warnings.Add(new JobWarning(JobWarningKind.PixelTooShortForTheGate, tooShort + " (engraving is refused)"));
        }

        if (OverscanMicrosteps == 0)
        {
            return warnings;
        }

        var bounds = Geometry.StageBounds();
        var left = bounds.Left - OverscanMicrosteps;
        var right = bounds.Right + OverscanMicrosteps;
        if (left < 0 || right > Geometry.TravelXMicrosteps)
        {
            var side = left < 0 && right > Geometry.TravelXMicrosteps ? "both edges" : left < 0 ? "the left edge" : "the right edge";
            warnings.Add(new JobWarning(
                JobWarningKind.OverscanClamped,
                $"overscan {Options.OverscanMm.ToString("0.###", CultureInfo.InvariantCulture)} mm reaches past the stage travel at {side} of the job: run-ups and run-outs there are shortened, so burning starts or stops while the stage is still changing speed"));
        }

        return warnings;
    }

    private List<JobWarning> ScanOffsetWarnings()
    {
        var warnings = new List<JobWarning>();
        if (ScanOffsetUm == 0 || Options.Strategy == PlanStrategy.Paper || !Options.Bidirectional)
        {
            return warnings;
        }

        var bounds = Geometry.StageBounds();
        var offset = StageUnits.UmToMicrosteps(ScanOffsetUm, Geometry.MicrostepUm);
        var left = JobGeometry.Round(bounds.Left + offset);
        var right = JobGeometry.Round(bounds.Right + offset);
        if (left < 0 || right > Geometry.TravelXMicrosteps)
        {
            warnings.Add(new JobWarning(
                JobWarningKind.OutsideTravel,
                $"scan offset {ScanOffsetUm.ToString("0.###", CultureInfo.InvariantCulture)} µm moves the right-to-left rows past the stage travel at the {(left < 0 ? "left" : "right")} edge: the stage will refuse those moves; move the job inwards"));
        }

        return warnings;
    }

    // Timed switching needs a run-up before and a run-out after every row's burn runs, inside the travel: a job whose
    // black reaches nearer the end of the travel than that brakes (or starts) over its outermost pixels there.
    private JobWarning? TimedRoomWarning()
    {
        long left = long.MaxValue, right = long.MinValue;
        for (var row = 0; row < Mask.Height; row++)
        {
            if (RowRuns.Extent(Mask.ReadRow(row), out var start, out var end))
            {
                left = Math.Min(left, Geometry.RunEdgeX(start, row));
                right = Math.Max(right, Geometry.RunEdgeX(end, row));
            }
        }

        var room = Math.Max(RunUpMicrosteps, RunOutMicrosteps);
        if (left == long.MaxValue || (left >= room && Geometry.TravelXMicrosteps - right >= room))
        {
            return null;
        }

        var roomMm = StageUnits.MicrostepsToMm(room, Geometry.MicrostepUm).ToString("0.###", CultureInfo.InvariantCulture);
        return new JobWarning(
            JobWarningKind.OverscanClamped,
            $"the job's black reaches within {roomMm} mm of the end of the stage travel: rows that start or end there accelerate or brake over their outermost pixels (more dose there); move the job at least {roomMm} mm in");
    }

    private struct NullVisitor : IMoveVisitor
    {
        public readonly void Visit(in Move move)
        {
        }
    }

    private sealed class CountingVisitor : IMoveVisitor
    {
        public int Count { get; set; }

        public void Visit(in Move move) => Count++;
    }

    private sealed class BufferVisitor : IMoveVisitor
    {
        public List<Move> Moves { get; } = [];

        public void Visit(in Move move) => Moves.Add(move);
    }
}
