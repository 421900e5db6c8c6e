using System.Runtime.CompilerServices;
using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Imaging;

namespace LaserEngrave.Core.Planning;

/// <summary>Plans a raster one image row at a time, keeping only what the next row needs (scan parity, where the stage stopped).</summary>
/// <remarks>
/// The single source of every plan's moves: <see cref="RasterPlan"/> enumerates, visits, counts and resumes through it,
/// so the executor, the statistics, the preview and the CSV all see the same sequence.
/// The hot methods are compiled fully optimised on their first call when compiled at run time (<see cref="HotPath"/>): one
/// statistics pass over a large mask is over before tiered compilation would have promoted them, and the CLI plans a mask
/// exactly once.
/// </remarks>
internal sealed class RowPlanner
{
    private readonly BitMask _mask;
    private readonly JobGeometry _geometry;
    private readonly bool _paper;
    private readonly bool _bidirectional;
    private readonly long _overscan;
    private readonly long _runUp;
    private readonly long _runOut;
    private readonly TimedSwitching? _timing;
    private readonly double _reverseOffset;
    private int[] _runs = new int[64];
    private long[] _edges = new long[64];
    private bool _hasPosition;
    private long _x;
    private long _y;

    public RowPlanner(BitMask mask, JobGeometry geometry, PlanOptions options, long overscanMicrosteps, double reverseOffsetMicrosteps, TimedSwitching? timing)
    {
        _timing = timing;
        _runUp = Math.Max(overscanMicrosteps, timing?.RunUpMicrosteps ?? 0);
        _runOut = Math.Max(overscanMicrosteps, timing?.RunOutMicrosteps ?? 0);
        _mask = mask;
        _geometry = geometry;
        _paper = options.Strategy == PlanStrategy.Paper;
        _bidirectional = options.Bidirectional;
        _overscan = overscanMicrosteps;
        _reverseOffset = reverseOffsetMicrosteps;
    }

    /// <summary>Index of the next row to plan; equals the mask height when every row is done.</summary>
    public int NextRow { get; private set; }

    /// <summary>Rows visited so far.</summary>
    public int VisitedRows { get; private set; }

    /// <summary>Direction of the row planned last (meaningful after it produced moves).</summary>
    public bool LastRowLeftToRight { get; private set; } = true;

    /// <summary>What the next row's planning depends on, to plan from a row on without planning the rows before (<see cref="PlanRowIndex"/>).</summary>
    public State Save() => new(NextRow, VisitedRows, LastRowLeftToRight, _hasPosition, _x, _y);

    /// <summary>Goes on from a <see cref="Save"/>d state: the rows planned next are those that followed it.</summary>
    public void Restore(in State state)
    {
        NextRow = state.NextRow;
        VisitedRows = state.VisitedRows;
        LastRowLeftToRight = state.LastRowLeftToRight;
        _hasPosition = state.HasPosition;
        _x = state.X;
        _y = state.Y;
    }

    /// <summary>Plans row <see cref="NextRow"/> into <paramref name="sink"/>; returns whether the row is visited (every row under Paper, non-blank rows under Optimized). Call only while NextRow &lt; height.</summary>
    [MethodImpl(HotPath.Optimized)]
    public bool PlanNextRow<TSink>(ref TSink sink)
        where TSink : IMoveVisitor
    {
        var row = NextRow++;
        var runCount = RowRuns.Find(_mask.ReadRow(row), ref _runs);
        if (_paper)
        {
            PlanPaperRow(ref sink, row, runCount);
        }
        else if (runCount == 0)
        {
            return false;
        }
        else
        {
            PlanOptimizedRow(ref sink, row, runCount, leftToRight: Direction(row, runCount, !_bidirectional || VisitedRows % 2 == 0));
        }

        VisitedRows++;
        return true;
    }

    [MethodImpl(HotPath.Optimized)]
    private void PlanPaperRow<TSink>(ref TSink sink, int row, int runCount)
        where TSink : IMoveVisitor
    {
        LastRowLeftToRight = true;
        var y = _geometry.RowY(row);
        var x = _geometry.RunEdgeX(0, row);
        if (_hasPosition)
        {
            Emit(ref sink, MoveKind.Travel, _x, _y, x, y, row);
        }

        var column = 0;
        for (var i = 0; i < runCount; i++)
        {
            int start = _runs[2 * i], end = _runs[(2 * i) + 1];
            if (start > column)
            {
                var whiteEnd = _geometry.RunEdgeX(start, row);
                Emit(ref sink, MoveKind.Travel, x, y, whiteEnd, y, row);
                x = whiteEnd;
            }

            var burnEnd = _geometry.RunEdgeX(end, row);
            Emit(ref sink, MoveKind.Burn, x, y, burnEnd, y, row);
            x = burnEnd;
            column = end;
        }

        if (column < _geometry.WidthPx)
        {
            var rowEnd = _geometry.RunEdgeX(_geometry.WidthPx, row);
            Emit(ref sink, MoveKind.Travel, x, y, rowEnd, y, row);
            x = rowEnd;
        }

        SetPosition(x, y);
    }

    [MethodImpl(HotPath.Optimized)]
    private void PlanOptimizedRow<TSink>(ref TSink sink, int row, int runCount, bool leftToRight)
        where TSink : IMoveVisitor
    {
        LastRowLeftToRight = leftToRight;
        if (_edges.Length < _runs.Length)
        {
            _edges = new long[_runs.Length];
        }

        // A right-to-left row's edges carry the scan offset, added before the one rounding.
        var offset = leftToRight ? 0 : _reverseOffset;
        for (var i = 0; i < 2 * runCount; i++)
        {
            _edges[i] = _geometry.RunEdgeX(_runs[i], row, offset);
        }

        var y = _geometry.RowY(row);
        var o = _timing is null ? _overscan : 0;
        var travel = _geometry.TravelXMicrosteps;
        var dir = leftToRight ? 1L : -1L;
        for (var j = 0; j < runCount; j++)
        {
            // A run is entered at its left edge going right and at its right edge going left.
            var i = leftToRight ? j : runCount - 1 - j;
            var entry = _edges[leftToRight ? 2 * i : (2 * i) + 1];
            var exit = _edges[leftToRight ? (2 * i) + 1 : 2 * i];
            if (j == 0)
            {
                var roomBefore = Math.Max(0, leftToRight ? entry : travel - entry);
                var runUp = entry - (dir * Math.Min(_runUp, roomBefore));
                if (_hasPosition)
                {
                    Emit(ref sink, MoveKind.Travel, _x, _y, runUp, y, row);
                }

                Emit(ref sink, MoveKind.Overscan, runUp, y, entry, y, row);
            }

            Emit(ref sink, MoveKind.Burn, entry, y, exit, y, row);

            if (j < runCount - 1)
            {
                var next = leftToRight ? i + 1 : i - 1;
                var nextEntry = _edges[leftToRight ? 2 * next : (2 * next) + 1];
                var gap = Math.Abs(nextEntry - exit);
                if (gap <= 2 * o || gap <= _runOut + _runUp || (_timing is not null && _timing.CrossesGap(gap)))
                {
                    // Crossed at the burn speed in one move, so the speed never dips: a gap no longer than two overscans,
                    // or (timed switching) one crossed sooner than a stop-go travel would take.
                    Emit(ref sink, MoveKind.Overscan, exit, y, nextEntry, y, row);
                }
                else
                {
                    Emit(ref sink, MoveKind.Overscan, exit, y, exit + (dir * _runOut), y, row);
                    Emit(ref sink, MoveKind.Travel, exit + (dir * _runOut), y, nextEntry - (dir * _runUp), y, row);
                    Emit(ref sink, MoveKind.Overscan, nextEntry - (dir * _runUp), y, nextEntry, y, row);
                }
            }
            else
            {
                var roomAfter = Math.Max(0, leftToRight ? travel - exit : exit);
                var runOut = exit + (dir * Math.Min(_runOut, roomAfter));
                Emit(ref sink, MoveKind.Overscan, exit, y, runOut, y, row);
                SetPosition(runOut, y);
            }
        }
    }

    // Timed switching needs its run-up inside the travel: a row whose first run starts too near the end it would be
    // entered from is scanned the other way, when there is room there.
    private bool Direction(int row, int runCount, bool preferred)
    {
        if (_timing is null)
        {
            return preferred;
        }

        var roomLeft = _geometry.RunEdgeX(_runs[0], row);
        var roomRight = _geometry.TravelXMicrosteps - _geometry.RunEdgeX(_runs[(2 * runCount) - 1], row);
        var fits = preferred ? roomLeft >= _runUp : roomRight >= _runUp;
        var otherFits = preferred ? roomRight >= _runUp : roomLeft >= _runUp;
        return fits || !otherFits ? preferred : !preferred;
    }

    private void SetPosition(long x, long y)
    {
        _hasPosition = true;
        _x = x;
        _y = y;
    }

    /// <summary>Passes a move on unless it goes nowhere (possible only with a pitch or overscan below one microstep, or an overscan of 0).</summary>
    private static void Emit<TSink>(ref TSink sink, MoveKind kind, long x0, long y0, long x1, long y1, int row)
        where TSink : IMoveVisitor
    {
        if (x0 != x1 || y0 != y1)
        {
            sink.Visit(new Move(kind, x0, y0, x1, y1, row));
        }
    }

    /// <summary>The planner between two rows (<see cref="Save"/>).</summary>
    internal readonly record struct State(int NextRow, int VisitedRows, bool LastRowLeftToRight, bool HasPosition, long X, long Y);
}
