namespace LaserEngrave.Core.Planning;

/// <summary>
/// Where each row of a raster plan that has moves starts: its first move's index, what was done before it and the
/// planner's state there. A stop point is found, and the moves after it made, from its row on, without planning the
/// rows before it: a resumed run costs the rows left, not the whole job again (each recovery of a long job resumes).
/// </summary>
internal sealed class PlanRowIndex
{
    private readonly PlanRowStart[] _rows;

    private PlanRowIndex(PlanRowStart[] rows, long moveCount)
    {
        _rows = rows;
        MoveCount = moveCount;
    }

    /// <summary>The plan's number of moves.</summary>
    public long MoveCount { get; }

    /// <summary>The rows with moves, in order.</summary>
    public IReadOnlyList<PlanRowStart> Rows => _rows;

    /// <summary>One pass of the planner over the whole plan.</summary>
    public static PlanRowIndex Build(RasterPlan plan)
    {
        var planner = plan.NewPlanner();
        var counter = new Counter();
        var rows = new List<PlanRowStart>();
        while (planner.NextRow < plan.Mask.Height)
        {
            var state = planner.Save();
            var before = counter;
            planner.PlanNextRow(ref counter);
            if (counter.Index > before.Index)
            {
                rows.Add(new PlanRowStart(state.NextRow, before.Index, before.Runs, before.Rows, before.LastRow, state));
            }
        }

        return new PlanRowIndex([.. rows], counter.Index);
    }

    /// <summary>The position in <see cref="Rows"/> of the last row starting at or before <paramref name="moveIndex"/> (before it, with <paramref name="strictly"/>); -1 when none does.</summary>
    public int RowHolding(long moveIndex, bool strictly = false)
    {
        int lo = 0, hi = _rows.Length - 1, found = -1;
        while (lo <= hi)
        {
            var mid = (lo + hi) >>> 1;
            var start = _rows[mid].MoveIndex;
            if (strictly ? start < moveIndex : start <= moveIndex)
            {
                found = mid;
                lo = mid + 1;
            }
            else
            {
                hi = mid - 1;
            }
        }

        return found;
    }

    /// <summary>The position in <see cref="Rows"/> of the first row at or after image row <paramref name="row"/>; <see cref="Rows"/>' count when none is.</summary>
    public int FirstRowFrom(int row)
    {
        int lo = 0, hi = _rows.Length;
        while (lo < hi)
        {
            var mid = (lo + hi) >>> 1;
            if (_rows[mid].Row < row)
            {
                lo = mid + 1;
            }
            else
            {
                hi = mid;
            }
        }

        return lo;
    }

    /// <summary>The moves of the row starting at <paramref name="start"/>.</summary>
    public static List<Move> RowMoves(RasterPlan plan, in PlanRowStart start)
    {
        var planner = plan.NewPlanner();
        planner.Restore(start.Planner);
        var buffer = new Buffer([]);
        planner.PlanNextRow(ref buffer);
        return buffer.Moves;
    }

    /// <summary>Every move from the row starting at <paramref name="start"/> to the end of the plan, one row at a time.</summary>
    public static IEnumerable<Move> MovesFrom(RasterPlan plan, PlanRowStart start)
    {
        var planner = plan.NewPlanner();
        planner.Restore(start.Planner);
        var buffer = new Buffer([]);
        while (planner.NextRow < plan.Mask.Height)
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
    /// Counts moves as <see cref="Programs.RasterProgram.ResumeAt"/> reports what was done before a resume point: burn
    /// runs, and rows finished (a row counts once a move of another row follows it).
    /// </summary>
    public struct Counter : IMoveVisitor
    {
        public Counter()
        {
        }

        public Counter(in PlanRowStart from)
        {
            Index = from.MoveIndex;
            Runs = from.RunsBefore;
            Rows = from.RowsBefore;
            LastRow = from.LastRowBefore;
        }

        public long Index { get; private set; }

        public long Runs { get; private set; }

        public int Rows { get; private set; }

        public int LastRow { get; private set; } = -1;

        public void Visit(in Move move)
        {
            Runs += move.Kind == MoveKind.Burn ? 1 : 0;
            if (move.Row != LastRow)
            {
                Rows += LastRow >= 0 ? 1 : 0;
                LastRow = move.Row;
            }

            Index++;
        }
    }

    private readonly struct Buffer(List<Move> moves) : IMoveVisitor
    {
        public List<Move> Moves { get; } = moves;

        public void Visit(in Move move) => Moves.Add(move);
    }
}

/// <summary>A row of a plan where it starts (<see cref="PlanRowIndex"/>).</summary>
/// <param name="Row">The image row.</param>
/// <param name="MoveIndex">Index of its first move.</param>
/// <param name="RunsBefore">Burn runs before it.</param>
/// <param name="RowsBefore">Rows finished before it, counted as <see cref="PlanRowIndex.Counter"/> does.</param>
/// <param name="LastRowBefore">The row of the last move before it (-1: none).</param>
/// <param name="Planner">The planner's state before planning it.</param>
internal readonly record struct PlanRowStart(int Row, long MoveIndex, long RunsBefore, int RowsBefore, int LastRowBefore, RowPlanner.State Planner);
